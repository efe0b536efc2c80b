#include "tools/controller/controller.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include "modules/module_setup.h"
#include "parser/address.h"
#include "parser/checker.h"
#include "parser/loader.h"
#include "vm/state_file.h"

namespace softslc {

// What every processor of one Controller (and its restores) is built from.
struct Controller::Loaded {
  Program program;
  RuntimeOptions options;
};

namespace {

std::string read_or_throw(const std::filesystem::path& p, const char* what) {
  std::ifstream f(p, std::ios::binary);
  if (!f) throw ControllerError(p.string() + ": error: cannot open the " + what + " file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void check(const RuntimeStatus& st, std::string_view call, std::string_view target) {
  if (!st) throw ControllerError(std::string(call) + " " + std::string(target) + ": " + st.message);
}

}  // namespace

Controller Controller::load(const std::filesystem::path& program, const std::optional<std::filesystem::path>& bench) {
  return from_text(read_or_throw(program, "program"), bench ? read_or_throw(*bench, "bench") : std::string(),
                   program.string(), bench ? bench->string() : std::string());
}

Controller Controller::from_text(std::string program_text, std::string bench_text, std::string name,
                                 std::string bench_name) {
  LoadResult lr = load_program_bytes(std::move(program_text), std::move(name));  // .SLC text or .RSS project
  if (!lr.ok()) throw ControllerError(lr.render_diagnostics());
  ModuleSetup setup = bench_text.empty() ? load_module_setup(*lr.program, std::nullopt)
                                         : load_module_setup_text(*lr.program, std::move(bench_text), std::move(bench_name));
  if (!setup.ok()) throw ControllerError(setup.render(lr.source_name, lr.source));
  auto loaded = std::make_shared<Loaded>();
  loaded->program = std::move(*lr.program);
  loaded->options = std::move(setup.options);
  Controller c(std::move(loaded));
  c.set_mode(Mode::Run);
  c.journal_.clear();  // the starting mode is part of the download state, not of a snapshot
  return c;
}

Controller::Controller(std::shared_ptr<const Loaded> loaded) : loaded_(std::move(loaded)) { fresh_runtime(); }
Controller::Controller(Controller&&) noexcept = default;
Controller& Controller::operator=(Controller&&) noexcept = default;
Controller::~Controller() = default;

void Controller::fresh_runtime() {
  RuntimeResult r = Runtime::create(loaded_->program, loaded_->options);
  if (!r.ok()) throw ControllerError("the program did not compile:\n" + r.render_errors());
  runtime_ = std::move(r.runtime);
}

std::string Controller::address_of(std::string_view target) const {
  if (const Symbol* s = loaded_->program.find_symbol(std::string(target)); s && !s->name.empty())
    return to_string(s->address);
  // The checker's address rules, as for `run --set` and test files: no bit 16-31, no slot or
  // element the program cannot name.
  if (auto a = parse_address(target))
    if (auto error = check_tool_address(loaded_->program, *a); !error.empty()) throw ControllerError(error);
  return std::string(target);
}

void Controller::apply(const ControllerCall& c, bool record) {
  Runtime& rt = *runtime_;
  switch (c.kind) {
    case ControllerCall::Kind::Set: check(rt.set(c.target, Value::of_int(c.integer)), "set", c.target); break;
    case ControllerCall::Kind::SetFloat: check(rt.set(c.target, Value::of_float(c.real)), "set", c.target); break;
    case ControllerCall::Kind::Force: check(rt.force(c.target, c.integer != 0), "force", c.target); break;
    case ControllerCall::Kind::Unforce: check(rt.unforce(c.target), "unforce", c.target); break;
    case ControllerCall::Kind::Scans: rt.scan(static_cast<int>(c.integer)); break;
    case ControllerCall::Kind::RunFor: rt.run_for(c.integer); break;
    case ControllerCall::Kind::SetMode: check(rt.set_mode(c.mode), "set_mode", to_string(c.mode)); break;
    case ControllerCall::Kind::ClearFault: rt.clear_fault(); break;
    case ControllerCall::Kind::Inject: check(rt.inject(c.target, c.change, c.args), "inject", c.target); break;
    case ControllerCall::Kind::SetWord: {
      // No address names one word of a string element, so the word is located from the
      // element's own location; the range was checked when the call was made.
      std::string error;
      auto a = parse_address(c.target, &error);
      std::optional<Location> loc;
      if (a) loc = rt.data().layout().locate(*a, &error);
      if (!loc) throw ControllerError("set_word " + c.target + ": " + error);
      const FileLayout& f = rt.data().layout().files[static_cast<std::size_t>(loc->file)];
      if (c.word < 0 || c.word >= f.words_per_element)
        throw ControllerError("set_word " + c.target + ": the element has words 0-" +
                              std::to_string(f.words_per_element - 1));
      rt.data().set_word(loc->word + static_cast<std::uint32_t>(c.word), static_cast<std::uint16_t>(c.integer));
      break;
    }
    case ControllerCall::Kind::RetrieveDataLog: rt.retrieve_data_log_record(static_cast<int>(c.integer)); break;
  }
  if (record && keep_journal_) journal_.push_back(c);
}

std::optional<std::string> Controller::retrieve_data_log_record(int queue) {
  if (!loaded_->program.find_data_log(queue))
    throw ControllerError("retrieve_data_log_record: data log queue " + std::to_string(queue) + " is not configured");
  auto text = runtime_->retrieve_data_log_record(queue);
  ControllerCall c;
  c.kind = ControllerCall::Kind::RetrieveDataLog;
  c.integer = queue;
  if (keep_journal_) journal_.push_back(c);
  return text;
}

std::vector<std::string> Controller::data_log_records(int queue) const {
  if (!loaded_->program.find_data_log(queue))
    throw ControllerError("data_log_records: data log queue " + std::to_string(queue) + " is not configured");
  return runtime_->data_log_records(queue);
}

void Controller::set(std::string_view target, std::int64_t value) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Set;
  c.target = address_of(target);
  c.integer = value;
  // A bit takes 0/1 (the runtime would take any non-zero integer as 1).
  if (auto a = parse_address(c.target); a && a->has_bit() && value != 0 && value != 1)
    throw ControllerError("set " + std::string(target) + ": a bit takes 0 or 1, not " + std::to_string(value));
  apply(c, true);
}

void Controller::set_float(std::string_view target, double value) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::SetFloat;
  c.target = address_of(target);
  c.real = value;
  apply(c, true);
}

Value Controller::get(std::string_view target) const {
  std::string error;
  auto v = runtime_->get(address_of(target), &error);
  if (!v) throw ControllerError("get " + std::string(target) + ": " + error);
  return *v;
}

void Controller::force(std::string_view target, bool on) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Force;
  c.target = address_of(target);
  c.integer = on ? 1 : 0;
  apply(c, true);
}

void Controller::unforce(std::string_view target) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Unforce;
  c.target = address_of(target);
  apply(c, true);
}

int Controller::scan(int n) {
  if (n < 0) throw ControllerError("scan: the count must not be negative");
  ControllerCall c;
  c.kind = ControllerCall::Kind::Scans;
  c.integer = n;
  if (keep_journal_) journal_.push_back(c);
  return runtime_->scan(n);
}

std::int64_t Controller::run_for(Nanoseconds duration) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::RunFor;
  c.integer = duration;
  if (keep_journal_) journal_.push_back(c);
  return runtime_->run_for(duration);
}

bool Controller::run_until(const std::function<bool(const Controller&)>& condition, Nanoseconds limit) {
  // Recorded as a run for the virtual time it took: run_for of that time runs the same whole
  // scans (the last one ends exactly then), so a replay reaches the same state.
  const VirtualTime start = runtime_->now();
  const bool held = runtime_->run_until([&](const Runtime&) { return condition(*this); }, limit);
  if (runtime_->now() > start) {
    ControllerCall c;
    c.kind = ControllerCall::Kind::RunFor;
    c.integer = runtime_->now() - start;
    if (keep_journal_) journal_.push_back(c);
  }
  return held;
}

VirtualTime Controller::now() const { return runtime_->now(); }
std::uint64_t Controller::scans() const { return runtime_->stats().scans; }

void Controller::set_mode(Mode m) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::SetMode;
  c.mode = m;
  apply(c, true);
}

Mode Controller::mode() const { return runtime_->mode(); }
const std::optional<FaultInfo>& Controller::fault() const { return runtime_->fault(); }

void Controller::clear_fault() {
  ControllerCall c;
  c.kind = ControllerCall::Kind::ClearFault;
  apply(c, true);
}

void Controller::inject(std::string_view device, std::string_view change, std::vector<std::string> args) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::Inject;
  c.target = std::string(device);
  c.change = std::string(change);
  c.args = std::move(args);
  apply(c, true);
}

std::vector<std::int64_t> Controller::observe(std::string_view device, std::string_view what) const {
  auto v = runtime_->observe(device, what);
  if (!v) throw ControllerError("observe " + std::string(device) + " '" + std::string(what) + "': no such device or observation");
  return *v;
}

std::vector<std::string> Controller::devices() const { return runtime_->devices(); }

Controller::Snapshot Controller::snapshot() const {
  Snapshot s;
  s.journal_ = journal_;
  return s;
}

void Controller::restore(const Snapshot& s) {
  fresh_runtime();
  journal_.clear();
  ControllerCall run;
  run.kind = ControllerCall::Kind::SetMode;
  run.mode = Mode::Run;
  apply(run, false);
  for (const auto& c : s.journal_) apply(c, true);
}

// ---- Data files word by word ----

std::optional<Controller::FileInfo> Controller::file_info(int number) const {
  if (number < 0 || number > 255) return std::nullopt;
  const FileLayout& f = runtime_->data().layout().files[static_cast<std::size_t>(number)];
  if (!f.present) return std::nullopt;
  FileInfo info;
  info.type = f.type;
  info.number = number;
  info.elements = f.elements;
  info.words_per_element = f.words_per_element;
  return info;
}

bool Controller::read_file_words(int number, std::uint32_t offset, std::span<std::uint16_t> out) const {
  auto info = file_info(number);
  if (!info || offset > info->words() || out.size() > info->words() - offset) return false;
  const FileLayout& f = runtime_->data().layout().files[static_cast<std::size_t>(number)];
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = runtime_->data().word(f.base + offset + static_cast<std::uint32_t>(i));
  return true;
}

namespace {

// The address of word `w` (0-based within the file) of an I or O file: the slot whose image
// holds it, and the word within the slot.
std::optional<Address> io_word_address(const DataTableLayout& L, FileType type, std::uint32_t w) {
  const auto& slots = type == FileType::Input ? L.input_slots : L.output_slots;
  for (int s = 0; s < kMaxSlots; ++s) {
    const SlotImage& img = slots[static_cast<std::size_t>(s)];
    if (img.present && w >= img.first && w < img.first + img.words) {
      Address a;
      a.type = type;
      a.file = static_cast<std::uint16_t>(fixed_file_number(type));
      a.element = s;
      a.word = static_cast<std::int32_t>(w - img.first);
      return a;
    }
  }
  return std::nullopt;
}

}  // namespace

Controller::WriteResult Controller::write_file_words(int number, std::uint32_t offset,
                                                     std::span<const std::uint16_t> values,
                                                     std::span<const std::uint16_t> masks) {
  WriteResult result;
  try {
    write_file_words_or_throw(number, offset, values, masks, result.calls);
  } catch (const ControllerError& e) {
    result.error = e.what();
  }
  return result;
}

void Controller::write_file_words_or_throw(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                                           std::span<const std::uint16_t> masks, std::vector<ControllerCall>& calls) {
  const std::string where = "write file " + std::to_string(number) + " word " + std::to_string(offset);
  auto info = file_info(number);
  if (!info) throw ControllerError(where + ": the file does not exist");
  if (masks.size() != values.size()) throw ControllerError(where + ": one mask per word");
  if (offset > info->words() || values.size() > info->words() - offset)
    throw ControllerError(where + ": " + std::to_string(values.size()) + " word(s) do not fit in the file");
  const DataTableLayout& L = runtime_->data().layout();
  const auto wpe = static_cast<std::uint32_t>(info->words_per_element);
  const auto emit = [&](ControllerCall c) {
    apply(c, true);
    calls.push_back(std::move(c));
  };
  std::vector<std::uint16_t> old(values.size());
  read_file_words(number, offset, old);
  const auto merged = [&](std::size_t i) {
    return static_cast<std::uint16_t>((old[i] & ~masks[i]) | (values[i] & masks[i]));
  };
  for (std::size_t i = 0; i < values.size();) {
    const std::uint32_t w = offset + static_cast<std::uint32_t>(i);
    Address a;
    a.type = info->type;
    a.file = static_cast<std::uint16_t>(number);
    a.element = static_cast<std::int32_t>(w / wpe);
    const int sub = static_cast<int>(w % wpe);
    if (masks[i] == 0) {
      ++i;
      continue;
    }
    if (is_io(info->type)) {
      auto io = io_word_address(L, info->type, w);
      if (!io) throw ControllerError(where + ": no slot holds image word " + std::to_string(w));
      a = *io;
    } else if (is_structured(info->type)) {
      a.word = sub;
    }
    if (info->type == FileType::Float || info->type == FileType::Long) {
      // A 32-bit value is written whole, from both of its words (the half outside the request
      // keeps its value), so a float never passes through a half-written pattern.
      std::uint16_t pair[2];
      read_file_words(number, w - static_cast<std::uint32_t>(sub), pair);
      pair[sub] = merged(i);
      if (sub == 0 && i + 1 < values.size()) pair[1] = merged(i + 1);
      std::uint32_t bits = static_cast<std::uint32_t>(pair[0]) | (static_cast<std::uint32_t>(pair[1]) << 16);
      ControllerCall c;
      c.target = to_string(a);
      if (info->type == FileType::Float) {
        float f;
        std::memcpy(&f, &bits, sizeof f);
        c.kind = ControllerCall::Kind::SetFloat;
        c.real = static_cast<double>(f);
      } else {
        c.kind = ControllerCall::Kind::Set;
        c.integer = static_cast<std::int32_t>(bits);
      }
      emit(std::move(c));
      i += (sub == 0 && i + 1 < values.size()) ? 2 : 1;
      continue;
    }
    if (info->type == FileType::String) {
      ControllerCall c;
      c.kind = ControllerCall::Kind::SetWord;
      c.target = to_string(a);
      c.word = sub;
      c.integer = merged(i);
      emit(std::move(c));
      ++i;
      continue;
    }
    if (masks[i] == 0xFFFF) {
      ControllerCall c;
      c.kind = ControllerCall::Kind::Set;
      c.target = to_string(a);
      c.integer = static_cast<std::int16_t>(values[i]);
      emit(std::move(c));
    } else {
      // A masked write changes only the masked bits: one bit write per bit, as `--set B3:0/4=1`.
      for (int b = 0; b < 16; ++b) {
        if (!((masks[i] >> b) & 1u)) continue;
        Address bit = a;
        bit.bit = b;
        ControllerCall c;
        c.kind = ControllerCall::Kind::Set;
        c.target = to_string(bit);
        c.integer = (values[i] >> b) & 1u;
        emit(std::move(c));
      }
    }
    ++i;
  }
}

void Controller::set_word(std::string_view element, int word, std::uint16_t value) {
  ControllerCall c;
  c.kind = ControllerCall::Kind::SetWord;
  c.target = address_of(element);
  c.word = word;
  c.integer = value;
  apply(c, true);
}

void Controller::perform(const ControllerCall& call) {
  switch (call.kind) {
    case ControllerCall::Kind::Scans: scan(static_cast<int>(call.integer)); break;
    case ControllerCall::Kind::RunFor: run_for(call.integer); break;
    default: apply(call, true); break;
  }
}

std::uint32_t Controller::data_digest() const {
  // The state file's CRC-32 over the words as the host stores them (little-endian on every
  // host softslc targets, as the state file assumes).
  const DataTable& d = runtime_->data();
  return crc32(d.words(), static_cast<std::size_t>(d.size()) * sizeof(std::uint16_t));
}

Runtime& Controller::runtime() { return *runtime_; }
const Runtime& Controller::runtime() const { return *runtime_; }
const Program& Controller::program() const { return loaded_->program; }

}  // namespace softslc
