#include "parser/checker.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "instructions/message_link.h"
#include "instructions/module_catalog.h"
#include "parser/rss/rss_reader.h"
#include "parser/expression.h"
#include "parser/loader.h"

namespace softslc {

namespace {

std::string mnemonic_of(const Instruction& in) { return std::string(spec(in.opcode).mnemonic); }

class Checker {
 public:
  Checker(Program& p, DiagnosticList& d, std::set<int> files_missing_rungs = {})
      : program_(p), diags_(d), files_missing_rungs_(std::move(files_missing_rungs)) {}

  // An address a tool reads or writes: the rules of a program operand, without recording the
  // file's type (a tool may name any file the program has).
  void check_tool_address(const Address& a) {
    // Status words: the runtime models one status file for every processor and refuses words
    // beyond it; a tool may set any of them (the 1747-SN examples' tests set S:33/13 on a 5/02,
    // which a program of that processor could not name — noted in docs/robustness.md). Only the
    // bit rule, which guards the shift, applies.
    if (a.type == FileType::Status) {
      if (a.bit > 15) error({}, "bit number " + std::to_string(a.bit) + " is out of range 0-15");
      return;
    }
    check_address(a, {}, OperandKind::Source, MFileAccess::OtherM, false);
  }

  void run() {
    add_embedded_io();
    check_slots();
    collect_symbols();
    collect_file_types();
    for (auto& file : program_.files) check_file(file);
    check_jsr_targets();
    check_data_blocks();
    check_sti_function_file();
    check_data_logs();
    check_forces();
    check_osr_storage();
  }

 private:
  Program& program_;
  DiagnosticList& diags_;
  std::set<int> files_missing_rungs_;  // a copy: the Checker may outlive a default argument
  std::map<std::string, const Symbol*> symbols_;
  struct MessageBlockUse {
    int file;
    int first;
    int last;
    SourcePos pos;
  };
  std::vector<MessageBlockUse> message_blocks_;  // the MSG control blocks seen so far
  struct RoutingUse {
    int file;
    int element;
    SourcePos pos;
  };
  std::vector<RoutingUse> routing_elements_;  // the RI elements channel 1 MSGs named so far
  // File number → first use (type and position), to catch one number used as two types.
  struct FileUse {
    FileType type;
    SourcePos pos;
  };
  std::map<int, FileUse> file_types_;
  std::vector<std::pair<Address, SourcePos>> osr_bits_;
  std::vector<std::pair<int, SourcePos>> jsr_targets_;
  std::vector<std::pair<int, SourcePos>> sts_targets_;
  std::vector<SourcePos> ml_sts_uses_;  // the MicroLogix STS (time only), which starts STI:0
  // the ISR files SLOT lines name with OPTION ISR=n (RM 11-27, 11-31).
  std::vector<std::pair<int, SourcePos>> isr_targets_;
  bool unknown_in_rung_ = false;  // the rung being checked names an unknown instruction

  void error(SourcePos p, std::string m) { diags_.error(p.line, p.column, std::move(m)); }
  void warning(SourcePos p, std::string m) { diags_.warning(p.line, p.column, std::move(m)); }

  // ---- Chassis ---------------------------------------------------------------------------------------

  // A MicroLogix's or fixed SLC 500's slot 0 is the controller's own I/O: when the program has no
  // SLOT 0 line, slot 0 comes with the processor (its catalog row in instructions/module_catalog.cpp).
  void add_embedded_io() {
    const std::string catalog = program_.processor.embedded_io_catalog();
    if (catalog.empty() || program_.find_slot(0)) return;
    auto entry = find_module_catalog(catalog);
    if (!entry) return;
    SlotConfig s;
    s.slot = 0;
    s.catalog = catalog;
    s.description = std::string(entry->description);
    s.scan_in = entry->default_scan_in;
    s.scan_out = entry->default_scan_out;
    s.pos = program_.processor_pos;
    s.implicit = true;
    program_.slots.insert(program_.slots.begin(), std::move(s));
  }

  void check_slots() {
    const std::string embedded = program_.processor.embedded_io_catalog();
    for (auto& slot : program_.slots) {
      if (!embedded.empty() && slot.slot == 0 && slot.catalog != embedded &&
          !resolve_processor(slot.catalog))
        error(slot.pos, "slot 0 of a " + program_.processor.display_name + " is the controller's embedded I/O (" +
                            embedded + "), not '" + slot.catalog + "'; expansion I/O starts at slot 1");
      if (slot.slot < 0 || slot.slot > 30) error(slot.pos, "slot number must be 0-30");
      // 1747-PT1 p. 4-5: a fixed controller's slot numbers are 0 (its own I/O) and 1-2, the left and
      // right slots of its two-slot expansion rack.
      if (program_.processor.family == ProcessorFamily::Fixed && slot.slot > 2 && slot.slot <= 30)
        error(slot.pos, "slot " + std::to_string(slot.slot) + ": the " + program_.processor.display_name + " (" +
                            program_.processor.catalog +
                            ") has its own I/O in slot 0 and a two-slot expansion rack, slots 1 and 2 (1747-PT1 p. 4-5)");
      if (slot.scan_in > 255 || slot.scan_out > 255) error(slot.pos, "SCAN_IN/SCAN_OUT must be 0-255 words");
      auto entry = find_module_catalog(slot.catalog);
      bool is_processor = slot.slot == 0 && resolve_processor(slot.catalog).has_value();
      if (!entry && !is_processor && !slot.m0_size && !slot.m1_size)
        warning(slot.pos, "unknown module catalog '" + slot.catalog +
                              "'; treated as a generic I/O card with SCAN_IN/SCAN_OUT words");
      if (slot.m0_size && (*slot.m0_size < 0 || *slot.m0_size > 4096)) error(slot.pos, "M0_SIZE must be 0-4096 words");
      if (slot.m1_size && (*slot.m1_size < 0 || *slot.m1_size > 4096)) error(slot.pos, "M1_SIZE must be 0-4096 words");
      check_isr_option(slot);
    }
  }

  // OPTION ISR=n: the slot's I/O interrupt subroutine file, "part of the I/O
  // configuration for each slot" (1747-RM001G p. 11-31), range 3-255 (p. 11-27).
  void check_isr_option(const SlotConfig& slot) {
    auto it = slot.options.find("ISR");
    if (it == slot.options.end()) return;
    if (!program_.processor.supports(Requirement::IoInterrupt)) {
      error(slot.pos, "OPTION ISR: the " + program_.processor.display_name + " has no I/O event interrupt; it needs " +
                          std::string(requirement_processors(Requirement::IoInterrupt)) + " (1747-RM001G p. 11-27)");
      return;
    }
    const std::string& v = it->second;
    int file = -1;
    if (!v.empty() && v.size() <= 3 && std::all_of(v.begin(), v.end(), [](char c) { return c >= '0' && c <= '9'; }))
      file = std::stoi(v);
    if (file < 3 || file > 255) {
      error(slot.pos, "OPTION ISR must name an interrupt subroutine file 3-255 (1747-RM001G p. 11-27), not '" + v + "'");
      return;
    }
    if (slot.slot < 1) error(slot.pos, "OPTION ISR: slot 0 is the processor; I/O interrupts come from slots 1-30");
    isr_targets_.emplace_back(file, slot.pos);
  }

  const SlotConfig* slot_of(int slot) const { return program_.find_slot(slot); }

  // ---- Symbols -----------------------------------------------------------------------------------------

  void collect_symbols() {
    for (auto& s : program_.symbols) {
      if (s.name.empty()) continue;
      if (s.automax && !resolve_automax_def(s)) continue;
      if (find_instruction(s.name) || s.name == "SOR" || s.name == "EOR" || s.name == "BST" || s.name == "NXB" ||
          s.name == "BND") {
        error(s.pos, "symbol '" + s.name + "' spells an instruction mnemonic; choose another name");
        continue;
      }
      auto [it, inserted] = symbols_.emplace(s.name, &s);
      if (!inserted) error(s.pos, "symbol '" + s.name + "' is defined twice (first at line " +
                                      std::to_string(it->second->pos.line) + ")");
      check_address(s.address, s.pos, OperandKind::Source, MFileAccess::OtherM, false);
    }
  }

  // True when `a` is in the file the program's MEMDEFs of its type are allocated in.
  bool uses_memdef_file(const Address& a) const {
    const char suffix = a.type == FileType::Bit && a.file == kMemdefBitFile       ? '@'
                        : a.type == FileType::Integer && a.file == kMemdefWordFile ? '%'
                                                                                    : 0;
    if (!suffix) return false;
    return std::any_of(program_.symbols.begin(), program_.symbols.end(), [&](const Symbol& s) {
      return s.automax && s.automax->kind == AutomaxDef::Kind::MemDef && s.automax->suffix == suffix;
    });
  }

  // ---- AutoMax IODEF / RIODEF / MEMDEF (parser/automax_def.h, docs/automax.md) -------------------------

  // Checks the fields of an AutoMax definition and sets the symbol's address; false (after
  // reporting, at the offending field) when the definition names no valid point.
  bool resolve_automax_def(Symbol& s) {
    const AutomaxDef& d = *s.automax;
    const std::string what = std::string(keyword_of(d.kind)) + " " + s.name + d.suffix;
    if (d.kind == AutomaxDef::Kind::MemDef) {
      s.address.type = d.suffix == '@' ? FileType::Bit : FileType::Integer;
      s.address.file = static_cast<std::uint16_t>(d.suffix == '@' ? kMemdefBitFile : kMemdefWordFile);
      s.address.element = d.suffix == '@' ? d.memdef_index / 16 : d.memdef_index;
      if (d.suffix == '@') s.address.bit = d.memdef_index % 16;
      return true;
    }
    const bool rio = d.kind == AutomaxDef::Kind::RioDef;
    std::vector<std::string_view> keys = rio ? std::vector<std::string_view>{"MASTER_SLOT", "DROP", "SLOT", "REGISTER"}
                                             : std::vector<std::string_view>{"SLOT", "REGISTER"};
    if (d.suffix == '@') keys.push_back("BIT");
    bool ok = true;
    auto field_error = [&](const AutomaxField& f, const std::string& m) {
      diags_.error(f.line, f.value_column, what + ": " + m);
      ok = false;
    };
    std::set<std::string> seen;
    for (const auto& f : d.fields) {
      if (!seen.insert(f.key).second) {
        diags_.error(f.line, f.column, what + ": field " + f.key + " is given twice");
        ok = false;
      } else if (std::find(keys.begin(), keys.end(), f.key) == keys.end()) {
        std::string known;
        for (auto k : keys) known += (known.empty() ? "" : ", ") + std::string(k);
        diags_.error(f.line, f.column, what + ": unknown field " + f.key + " (a " + std::string(keyword_of(d.kind)) +
                                           " " + (d.suffix == '@' ? "bit" : "register") + " takes " + known + ")");
        ok = false;
      } else if (f.value < 0) {
        ok = false;  // not a number: reported by the loader
      }
    }
    for (auto k : keys)
      if (!d.field(k)) {
        error(s.pos, what + ": missing field " + std::string(k) +
                         (k == "BIT" ? " (a name ending in '@' is a bit)" : ""));
        ok = false;
      }
    if (!ok) return false;
    auto in_range = [&](std::string_view key, int lo, int hi, const char* why) {
      const AutomaxField& f = *d.field(key);
      if (f.value >= lo && f.value <= hi) return true;
      field_error(f, std::string(key) + " must be " + std::to_string(lo) + "-" + std::to_string(hi) + " (" + why + ")");
      return false;
    };
    const AutomaxField& master = *d.field(rio ? "MASTER_SLOT" : "SLOT");
    if (in_range(master.key, 1, 30, "the chassis slot of the 57C416 master")) {
      const SlotConfig* slot = slot_of(static_cast<int>(master.value));
      if (!slot || slot->catalog != kAutomaxMasterCatalog)
        field_error(master, "slot " + std::to_string(master.value) + " holds no AutoMax Remote I/O master (a SLOT " +
                                std::to_string(master.value) + " " + kAutomaxMasterCatalog + " line)");
    }
    if (d.suffix == '@') in_range("BIT", 0, 15, "registers are 16 bits");
    if (!rio) {
      if (in_range("REGISTER", 0, kAutomaxAreaWords - 1, "drop 0 registers, figure 4.1"))
        s.address.word = automax_master_word(static_cast<int>(d.field("REGISTER")->value));
    } else {
      const AutomaxField& drop = *d.field("DROP");
      if (drop.value == 8 || drop.value < 1 || drop.value > 15)
        field_error(drop, "DROP must be 1-7, or 9-F for an all-digital Shark rack (section 4.4)");
      in_range("SLOT", 0, kAutomaxSlots - 1, "rack slots of a drop");
      in_range("REGISTER", 0, kAutomaxSlotRegisters - 1, "registers of a slot in the drop's image area");
      if (ok)
        s.address.word = automax_drop_word(automax_image_area(static_cast<int>(drop.value)),
                                           static_cast<int>(d.field("SLOT")->value),
                                           static_cast<int>(d.field("REGISTER")->value));
    }
    // cppcheck-suppress identicalConditionAfterEarlyExit ; in_range and the MASTER check clear ok (field_error)
    if (!ok) return false;
    s.address.type = FileType::M0;
    s.address.file = 0;
    s.address.element = static_cast<std::uint16_t>(master.value);
    if (d.suffix == '@') s.address.bit = static_cast<int>(d.field("BIT")->value);
    return true;
  }

  void resolve(Operand& op) {
    if (op.kind != Operand::Kind::Symbol || op.resolved) return;
    auto it = symbols_.find(op.spelling);
    if (it == symbols_.end()) return;
    op.address = it->second->address;
    op.resolved = true;
  }

  // ---- File numbers and types ---------------------------------------------------------------------------

  void note_file_use(const Address& a, SourcePos pos) {
    if (is_mfile(a.type) || is_function_file(a.type) || a.indirect_file()) return;
    auto [it, inserted] = file_types_.emplace(a.file, FileUse{a.type, pos});
    if (!inserted && it->second.type != a.type)
      error(pos, "file " + std::to_string(a.file) + " is used as " + std::string(file_letter(a.type)) +
                     std::to_string(a.file) + " here but as " + std::string(file_letter(it->second.type)) +
                     std::to_string(a.file) + " at line " + std::to_string(it->second.pos.line));
  }

  void collect_file_types() {
    // DATA blocks first: they declare the files as the export defines them.
    for (const auto& d : program_.data)
      if (d.type) {
        Address a;
        a.type = *d.type;
        a.file = static_cast<std::uint16_t>(d.file);
        note_file_use(a, d.pos);
      }
  }

  // ---- Addresses ---------------------------------------------------------------------------------------

  bool check_indirect_ref(const IndirectRef& r, SourcePos pos) {
    if (r.element > 255) {
      error(pos, "element " + std::to_string(r.element) + " of " + to_string(r) + " is beyond 255");
      return false;
    }
    return true;
  }

  // Function files (RTC:0.YR ...): MicroLogix 1100-class only, and only the ones softslc models.
  void check_function_file_address(const Address& a, SourcePos pos) {
    const auto& proc = program_.processor;
    const std::string name(function_file_name(a.file));
    if (!proc.is_micrologix_1100_class()) {
      error(pos, "function file " + name + " exists on the MicroLogix 1100, 1200, 1400 and 1500 only; this "
                 "program's processor is " + proc.display_name);
      return;
    }
    if (!function_file_simulated(a.file)) {
      error(pos, "function file " + name + " (" + to_string(a) + ") is not simulated by softslc yet; only RTC, STI, EII, HSC, PTO/PTOX, DLS and CS0:4/MCP are");
      return;
    }
    if (is_pulse_train_file(a.file) && !check_pulse_train_name(a.file, pos)) return;
    if (const int channel = communications_status_channel(a.file); channel >= 0)
      return check_communications_status_address(a, channel, pos);
    if (is_data_log_status_file(a.file)) {
      // "The DLS file does not exist until a data log queue has been configured" (1763-RM001C p. 440).
      if (!proc.has_data_logging())
        error(pos, "the Data Log Status file " + to_string(a) + " exists on the " +
                       std::string(requirement_processors(Requirement::MicroLogixDataLog)) + " only (AG-UM008C p. 3-58); "
                       "this program's processor is " + proc.display_name);
      else if (!program_.find_data_log(a.element))
        error(pos, to_string(a) + ": data log queue " + std::to_string(a.element) +
                       " is not configured (no DATALOG " + std::to_string(a.element) +
                       "); the DLS file has an element for each configured queue only (1763-RM001C p. 440)");
      else if (a.word == dls::kBits && a.bit < 0)
        error(pos, to_string(a) + ": word 0 of a DLS element is addressable by bit only (EN, DN, OV; AG-UM008C p. 3-64)");
      if (a.word >= dls::kWords) error(pos, to_string(a) + ": DLS elements have words 0-2 (FSZ is 1, RST is 2)");
      return;
    }
    if (a.file == static_cast<int>(FunctionFile::HSC)) {
      if (a.element >= proc.hsc_count())
        error(pos, to_string(a) + ": the " + proc.display_name + " has " + std::to_string(proc.hsc_count()) +
                       " high-speed counter(s), HSC:0" + (proc.hsc_count() > 1 ? " to HSC:" + std::to_string(proc.hsc_count() - 1) : "") +
                       " (docs/semantics.md \"The HSC function file\")");
    } else if (a.file == static_cast<int>(FunctionFile::EII)) {
      if (a.element >= proc.eii_count())
        error(pos, to_string(a) + ": the " + proc.display_name + " has " + std::to_string(proc.eii_count()) +
                       " event input interrupts, EII:0 to EII:" + std::to_string(proc.eii_count() - 1) +
                       " (1763-RM001C p. 272; docs/semantics.md \"The EII function file\")");
    } else if (a.element >= function_file_elements(a.file))
      error(pos, to_string(a) + ": " + name + (function_file_elements(a.file) == 1
                                                   ? " has element 0 only"
                                                   : " has elements 0-" + std::to_string(function_file_elements(a.file) - 1)));
    if (a.word >= function_file_words_per_element(a.file))
      error(pos, to_string(a) + ": " + name + " elements have words 0-" +
                     std::to_string(function_file_words_per_element(a.file) - 1));
  }

  // The communications status files (docs/semantics.md "The CS file"): CS0 on every MicroLogix 1100-1500,
  // CS1 on the 1764-LRP (its second serial port; the 1100/1400's channel 1 is Ethernet, whose status file
  // is ES), CS2 on the 1400. softslc keeps one bit of them, CS0:4/MCP; the others are refused by name.
  void check_communications_status_address(const Address& a, int channel, SourcePos pos) {
    const auto& proc = program_.processor;
    const std::string file = "CS" + std::to_string(channel);
    if (channel == 1 && proc.micrologix != MicroLogixModel::ML1500LRP)
      return error(pos, to_string(a) + ": the " + proc.display_name + " has no CS1 file (1762-RM001C p. 3-13: CS1 is "
                                       "channel 1 of the 1764-LRP; 1763-RM001C p. 57, 1766-RM001A p. 63: the 1100/1400's "
                                       "channel 1 is Ethernet, its status file ES)");
    if (channel == 2)
      return error(pos, to_string(a) + ": " +
                            (proc.micrologix == MicroLogixModel::ML1400
                                 ? std::string("the MicroLogix 1400's channel 2 is not simulated by softslc, nor its CS2 file")
                                 : "the " + proc.display_name + " has no channel 2 (CS2 is the MicroLogix 1400's, 1766-RM001A p. 63)"));
    if (a.element < 0 || a.element >= cs::kElements || a.word > 0)
      return error(pos, to_string(a) + ": " + file + " has 71 one-word elements, " + file + ":0 to " + file +
                            ":70 (1762-RM001C p. 3-13 Table 3.9)");
    if (a.element != cs::kStatusElement || a.bit != cs::kCommandPendingBit)
      error(pos, to_string(a) + " is not simulated by softslc: of the communications status file it keeps " + file +
                     ":4/MCP, the outgoing message command pending bit (1762-RM001C p. 21-27 Table 21.5), only; "
                     "docs/semantics.md \"The CS file\"");
  }

  // DATALOG statements: the queue configuration RSLogix keeps in the project (1763-RM001C pp.
  // 433-437, 1766-RM001A pp. 518-523, AG-UM008C pp. 3-58..3-63). Each record's formatted string
  // fits the controller's limit and all queues fit its data log memory.
  void check_data_logs() {
    const auto& proc = program_.processor;
    std::int64_t bytes = 0;
    std::set<int> seen;
    for (auto& q : program_.data_logs) {
      const std::string name = "DATALOG " + std::to_string(q.number);
      if (!proc.has_data_logging()) {
        error(q.pos, name + ": data logging is available on the " +
                         std::string(requirement_processors(Requirement::MicroLogixDataLog)) +
                         " only (AG-UM008C p. 3-58, 1766-RM001A p. 518); this program's processor is " + proc.display_name);
        continue;
      }
      if (q.number < 0 || q.number >= dls::kMaxQueues) {
        error(q.pos, name + ": queue numbers are 0-255 (1763-RM001C p. 433)");
        continue;
      }
      if (!seen.insert(q.number).second) error(q.pos, name + " is configured twice");
      if (q.records < 1) error(q.pos, name + ": a queue holds at least 1 record");
      int characters = (q.date ? 10 : 0) + (q.time ? 8 : 0);
      int record_bytes = 2 + (q.date ? 2 : 0) + (q.time ? 2 : 0);  // + the 2-byte integrity check
      int items = (q.date ? 1 : 0) + (q.time ? 1 : 0);
      for (std::size_t i = 0; i < q.fields.size(); ++i) {
        const Address& a = q.fields[i];
        const SourcePos pos = q.field_pos[i];
        const std::string what = name + " field " + to_string(a);
        if (a.is_indirect() || a.indexed || a.has_bit() || a.type == FileType::String || is_function_file(a.type) ||
            is_mfile(a.type) || (is_structured(a.type) && a.word < 0)) {
          error(pos, what + ": a field is a direct word (N7:11, T4:5.ACC, I1:3.0), long word (L14:0) or, on the "
                            "MicroLogix 1400, floating-point (F8:0) address (1763-RM001C p. 434, 1766-RM001A p. 519); "
                            "softslc does not log bits, strings or function files");
          continue;
        }
        if (a.type == FileType::Float && proc.micrologix != MicroLogixModel::ML1400) {
          error(pos, what + ": the " + proc.display_name + " logs words and long words only (1763-RM001C p. 434; the "
                            "MicroLogix 1400 adds float, 1766-RM001A p. 519)");
          continue;
        }
        check_address(a, pos, OperandKind::Source, MFileAccess::NoM);
        const bool long_word = a.type == FileType::Long, real = a.type == FileType::Float;
        characters += real ? 13 : long_word ? 11 : 6;
        record_bytes += long_word || real ? 4 : 2;
        ++items;
      }
      if (items == 0) {
        error(q.pos, name + ": a record needs a date or time stamp or a field");
        continue;
      }
      characters += items - 1;  // a delimiter between items
      if (characters > proc.data_log_max_characters())
        error(q.pos, name + ": the formatted record is " + std::to_string(characters) + " characters; the " +
                         proc.display_name + " allows " + std::to_string(proc.data_log_max_characters()) +
                         " (date 10, time 8, word 6, long word 11, float 13, 1 per delimiter: 1763-RM001C p. 435, "
                         "1766-RM001A p. 519)");
      bytes += static_cast<std::int64_t>(std::max(q.records, 0)) * record_bytes;
    }
    if (proc.has_data_logging() && bytes > proc.data_log_bytes())
      error(program_.data_logs.front().pos,
            "the DATALOG queues need " + std::to_string(bytes) + " bytes; the " + proc.display_name + " has " +
                std::to_string(proc.data_log_bytes()) + " bytes of data log memory (records x record size, a record "
                "2 bytes per word, date and time, 4 per long word, plus a 2-byte integrity check: 1763-RM001C p. 435)");
  }

  // The pulse train output file is PTO on the MicroLogix 1100, 1200 and 1500 and PTOX on the 1400
  // (1763-RM001C p. 136, 1762-RM001C p. 6-9, 1766-RM001A p. 146): the other name is refused.
  bool check_pulse_train_name(int file, SourcePos pos) {
    const bool ml1400 = program_.processor.micrologix == MicroLogixModel::ML1400;
    if (ml1400 == (file == static_cast<int>(FunctionFile::PTOX))) return true;
    error(pos, std::string(ml1400 ? "the MicroLogix 1400's pulse train output file is PTOX (1766-RM001A p. 146), not PTO"
                                  : "PTOX is the MicroLogix 1400's pulse train output file; the " + program_.processor.display_name +
                                        "'s is PTO (1763-RM001C p. 136, 1762-RM001C p. 6-9)"));
    return false;
  }

  // A program write into a function file: the manuals' "read only" sub-elements (STI:0.PFN, /UIX, ...;
  // function_sub_element_writable) are refused, as RSLogix refuses them. A file operand written into
  // the STI (COP, CPW) would cover read-only words too, so the STI is written one sub-element at a
  // time (docs/semantics.md "MicroLogix").
  void check_function_file_write(const Operand& op, const OperandSpec& os, const std::string& where) {
    const Address& a = op.address;
    if (is_pulse_train_file(a.file)) return check_pulse_train_write(op, os, where);
    const bool hsc = a.file == static_cast<int>(FunctionFile::HSC);
    const bool eii = a.file == static_cast<int>(FunctionFile::EII);
    const bool dls = is_data_log_status_file(a.file);
    if (communications_status_channel(a.file) >= 0)
      return error(op.pos, where + ": " + to_string(a) + ": the communications status file is read only "
                                                         "(1762-RM001C p. 3-13)");
    if (a.file != static_cast<int>(FunctionFile::STI) && !hsc && !eii && !dls) return;
    const std::string name(function_file_name(a.file));
    if (os.kind == OperandKind::File)
      return error(op.pos, where + ": the " + name + " function file is written one sub-element at a time (MOV, OTL, "
                                   "...); a file instruction would also write its read-only words");
    if (a.word >= 0 && !function_sub_element_writable(a.file, a.word, a.bit))
      error(op.pos, where + ": " + to_string(a) + " is read only to the user program (" +
                        (hsc   ? "1762-RM001C ch. 5; docs/semantics.md \"The HSC function file\")"
                         : eii ? "1763-RM001C p. 275; docs/semantics.md \"The EII function file\")"
                         : dls ? "only OV is the program's to clear, AG-UM008C p. 3-65; docs/semantics.md \"Data logging\")"
                               : "1763-RM001C pp. 270-272; docs/semantics.md \"MicroLogix\")"));
  }

  // A program write into an MG element: only CHN, NOD, MTO, TFN, ELE and the control bits are read/write
  // (the access column of 1762-RM001C p. 21-4, 1763-RM001B pp. 347-348, 1766-RM001A pp. 399-400); the
  // status bits (p. 21-6), ERR and the rest are read only. A whole element or a file operand would cover
  // read-only words too, so an MG element is written one sub-element at a time.
  void check_message_file_write(const Operand& op, const OperandSpec& os, const std::string& where) {
    const Address& a = op.address;
    if (os.kind == OperandKind::File)
      return error(op.pos, where + ": an MG element is written one sub-element at a time (MOV, OTL, ...); a file "
                                   "instruction would also write its read-only words (1762-RM001C p. 21-4)");
    if (a.indirect_word()) return;
    if (a.word < 0 || !message_sub_element_writable(a.word, a.bit))
      error(op.pos, where + ": " + to_string(a) + " is read only to the user program (1762-RM001C pp. 21-4, 21-6; "
                                                  "1766-RM001A pp. 399-400: CHN, NOD, MTO, TFN, ELE and the control "
                                                  "bits EN, TO are read/write)");
  }

  // PTO:0/DN, .OPP, .OUT ... are the PTO sub-system's (read only); OF, TOP, ADP, JF, RP, EH, CS, JP, JC
  // are the program's (1762-RM001C pp. 6-9..6-12; the rest [U], docs/semantics.md "The PTO function file").
  void check_pulse_train_write(const Operand& op, const OperandSpec& os, const std::string& where) {
    const Address& a = op.address;
    const std::string name(function_file_name(a.file));
    if (os.kind == OperandKind::File)
      return error(op.pos, where + ": the " + name + " function file is written one sub-element at a time (MOV, OTE, "
                                   "...); a file instruction would also write its read-only words");
    if (a.word >= 0 && !function_sub_element_writable(a.file, a.word, a.bit))
      return error(op.pos, where + ": " + to_string(a) + " is read only to the user program (1762-RM001C pp. 6-9..6-12; "
                                                        "docs/semantics.md \"The PTO function file\")");
    // Jog (JP, JC, JF) is accepted but does nothing in softslc: say so where the program asks for it.
    const auto sub = a.bit >= 0 ? function_bit_name(a.file, a.word, a.bit) : function_word_name(a.file, a.word);
    if (sub == "JP" || sub == "JC" || sub == "JF")
      warning(op.pos, where + ": " + to_string(a) + ": softslc does not simulate the PTO's jog; no pulses come of it "
                                                   "(docs/semantics.md \"The PTO function file\")");
  }

  // Checks an address on its own. `kind` and `mfile` say where it stands (for M-file rules).
  void check_address(const Address& a, SourcePos pos, OperandKind kind, MFileAccess mfile, bool record_type = true) {
    const auto& proc = program_.processor;
    if (is_function_file(a.type)) {
      if (a.bit > 15) error(pos, "bit number " + std::to_string(a.bit) + " is out of range 0-15");
      check_function_file_address(a, pos);
      return;
    }
    if (record_type) note_file_use(a, pos);
    if (a.bit > 15) error(pos, "bit number " + std::to_string(a.bit) + " is out of range 0-15");
    if (a.is_indirect() && !proc.has_indirect_addressing())
      error(pos, "indirect addressing needs SLC 5/03 OS302, 5/04 OS401, 5/05, MicroLogix 1100 or 1400; this "
                 "program's processor is " + proc.display_name);
    for (const auto* r : {&a.indirect_file(), &a.indirect_element(), &a.indirect_word(), &a.indirect_bit()})
      if (*r) check_indirect_ref(**r, pos);
    switch (a.type) {
      case FileType::Float:
        if (!proc.has_float_files()) error(pos, "F files need SLC 5/03 OS301 or later; this program's processor is " +
                                                    proc.display_name);
        if (a.has_bit()) error(pos, "a floating-point element has no bits");
        break;
      case FileType::Long:
        if (!proc.has_long_files())
          error(pos, "L (long integer) files exist on MicroLogix only (the 1100, 1200, 1400 and 1500, not the "
                     "1000); this program's processor is " + proc.display_name);
        break;
      case FileType::Message:
        if (!proc.has_message_files())
          error(pos, "MG (message) files exist on the MicroLogix 1100, 1200, 1400 and 1500 only (1762-RM001C p. 21-4, "
                     "1766-RM001A p. 399); the SLC MSG keeps its control block in an N file (1747-RM001G p. 12-31); "
                     "this program's processor is " + proc.display_name);
        if (!a.indirect_word() && a.word >= mg::kWords) error(pos, "an MG element has sub-elements 0-24 (1762-RM001C p. 21-4)");
        break;
      case FileType::Routing:
        if (!proc.has_routing_files())
          error(pos, "RI (routing information) files exist on the MicroLogix 1100 and 1400 only, for channel 1 "
                     "Ethernet messages (1763-RM001B p. 384, 1766-RM001A p. 435); this program's processor is " +
                     proc.display_name);
        if (!a.indirect_word() && a.word >= ri::kWords) error(pos, "an RI element has words 0-19 (1766-RM001A p. 435)");
        break;
      case FileType::String:
      case FileType::Ascii:
        if (proc.family == ProcessorFamily::Slc501 || proc.family == ProcessorFamily::Slc502 ||
            proc.family == ProcessorFamily::Fixed)
          error(pos, std::string(file_letter(a.type)) + " files need SLC 5/03 or later");
        break;
      default: break;
    }
    if (!is_io(a.type) && !is_mfile(a.type) && a.type != FileType::Status && !a.indirect_file()) {
      if (a.file < 3) error(pos, "files 0-2 are O, I and S; data files are numbered 3-255");
    }
    if (!a.indirect_element() && !is_io(a.type) && !is_mfile(a.type) && a.type != FileType::Status && a.element > 255)
      error(pos, "element " + std::to_string(a.element) + " is beyond the largest file size (elements 0-255)");
    if (is_structured(a.type) && !a.indirect_word() && a.word > 2)
      error(pos, "a " + std::string(file_letter(a.type)) + " element has words 0-2 only");
    if (a.type == FileType::Status && !a.indirect_element() && a.element >= status_file_words(proc))
      error(pos, "S:" + std::to_string(a.element) + " is beyond the status file of " + proc.display_name + " (S:0-S:" +
                     std::to_string(status_file_words(proc) - 1) + ")");
    if (is_io(a.type)) check_io_address(a, pos);
    if (is_mfile(a.type)) check_mfile_address(a, pos, kind, mfile);
  }

  void check_io_address(const Address& a, SourcePos pos) {
    if (a.indirect_element()) return;
    if (a.element > 30) {
      error(pos, "slot " + std::to_string(a.element) + " is beyond the chassis (slots 0-30)");
      return;
    }
    const SlotConfig* slot = slot_of(a.element);
    if (!slot) {
      error(pos, "slot " + std::to_string(a.element) + " has no module (no SLOT " + std::to_string(a.element) +
                     " line)");
      return;
    }
    int words = a.type == FileType::Input ? slot->scan_in : slot->scan_out;
    if (!a.indirect_word() && a.word_in_element() >= words)
      error(pos, std::string(a.type == FileType::Input ? "input" : "output") + " word " +
                     std::to_string(a.word_in_element()) + " is beyond slot " + std::to_string(a.element) + "'s " +
                     std::to_string(words) + "-word " + (a.type == FileType::Input ? "input" : "output") +
                     " image (" + slot->catalog + ")");
  }

  void check_mfile_address(const Address& a, SourcePos pos, OperandKind kind, MFileAccess mfile) {
    if (mfile == MFileAccess::NoM) {
      error(pos, "M0/M1 addresses are not allowed here (1747-SN manual p. B-2: not in OSR, nor in the file "
                 "parameter of BSL, BSR, SQO, SQC, SQL, LFL, LFU, FFL, FFU)");
      return;
    }
    if (a.indirect_element()) return;
    const SlotConfig* slot = slot_of(a.element);
    if (!slot) {
      error(pos, "slot " + std::to_string(a.element) + " has no module (no SLOT " + std::to_string(a.element) +
                     " line)");
      return;
    }
    int size = a.type == FileType::M0 ? m0_words(*slot) : m1_words(*slot);
    if (size == 0) {
      error(pos, "the module in slot " + std::to_string(a.element) + " (" + slot->catalog + ") has no " +
                     std::string(file_letter(a.type)) + " file");
      return;
    }
    int span = 1;
    (void)kind;
    if (!a.indirect_word() && a.word_in_element() + span > size)
      error(pos, std::string(file_letter(a.type)) + " word " + std::to_string(a.word_in_element()) +
                     " is beyond the " + std::to_string(size) + "-word " + std::string(file_letter(a.type)) +
                     " file of slot " + std::to_string(a.element) + " (" + slot->catalog + ")");
  }

  // ---- Operands -----------------------------------------------------------------------------------------

  void check_operand(const Instruction& in, Operand& op, const OperandSpec& os) {
    if (!keyword_words(os.kind).empty()) return check_keyword(in, op, os);
    resolve(op);
    // "TON timer": built only for a diagnostic, since a program has millions of clean operands
    // (building it for each was 4% of loading a 1M-rung program, docs/performance.md "Load time").
    const auto where = [&] { return mnemonic_of(in) + " " + std::string(os.label); };
    if (op.kind == Operand::Kind::Symbol && !op.resolved) {
      error(op.pos, "unknown symbol '" + op.text() + "' (" + where() + ")");
      return;
    }
    if (op.kind == Operand::Kind::Address && uses_memdef_file(op.address))
      return error(op.pos, where() + ": " + std::string(file_letter(op.address.type)) + std::to_string(op.address.file) +
                               " holds the program's MEMDEF variables; name them instead (docs/automax.md)");
    if (op.is_address() && is_function_file(op.address.type) && os.access != OperandAccess::Read)
      check_function_file_write(op, os, where());
    // The MicroLogix MSG's own MG element is the instruction's state, which the processor writes; the
    // program's writes into an MG element are held to the access column.
    if (op.is_address() && is_message_file(op.address.type) && os.access != OperandAccess::Read &&
        os.kind != OperandKind::MessageElement)
      check_message_file_write(op, os, where());
    if (op.kind == Operand::Kind::Symbol && os.access != OperandAccess::Read) {
      const Symbol* sym = symbols_.at(op.spelling);
      if (sym->automax && sym->automax->kind == AutomaxDef::Kind::IoDef)
        return error(op.pos, where() + ": " + op.text() + " is an IODEF point of drop 0, and drop 0 registers are read "
                                                        "only (AutoMax Remote I/O manual, section 4.2)");
    }
    auto expect = [&](std::string_view what) {
      error(op.pos, where() + ": expected " + std::string(what) + ", found '" + op.text() + "'");
    };
    switch (os.kind) {
      case OperandKind::Bit:
        if (!op.is_address()) return expect("a bit address");
        if (!op.address.has_bit()) return expect("a bit address (for example B3:0/1 or T4:0/DN)");
        break;
      case OperandKind::Source:
      case OperandKind::WordSource:
        if (os.kind == OperandKind::WordSource && op.kind == Operand::Kind::Float)
          return error(op.pos, where() + ": " + mnemonic_of(in) + " works on integer words; a floating-point constant is not allowed");
        if (os.kind == OperandKind::WordSource && op.is_address() && op.address.type == FileType::Float)
          return error(op.pos, where() + ": " + mnemonic_of(in) + " works on integer words; an F address is not allowed");
        if (op.kind == Operand::Kind::Float && !program_.processor.has_float_files())
          return error(op.pos, "floating-point constants need SLC 5/03 OS301 or later");
        if (op.is_number()) {
          if (op.kind == Operand::Kind::Integer && (op.integer < -32768 || op.integer > 65535) &&
              program_.processor.family != ProcessorFamily::MicroLogix)
            return error(op.pos, where() + ": constant " + op.text() + " does not fit a 16-bit word");
          return;
        }
        if (op.address.has_bit()) return expect("a word address or a constant");
        if (is_structured(op.address.type) && op.address.word < 0)
          return expect("a word of the element (.PRE, .ACC, .LEN or .POS)");
        break;
      case OperandKind::Dest:
      case OperandKind::WordDest:
        if (!op.is_address()) return expect("a destination word address");
        if (os.kind == OperandKind::WordDest && op.address.type == FileType::Float)
          return error(op.pos, where() + ": " + mnemonic_of(in) + " works on integer words; an F address is not allowed");
        if (op.address.has_bit()) return expect("a word address, not a bit");
        if (is_structured(op.address.type) && op.address.word < 0)
          return expect("a word of the element (.PRE, .ACC, .LEN or .POS)");
        break;
      case OperandKind::File:
        if (!op.is_address()) return expect("a file address such as #N7:0");
        if (op.address.has_bit()) return expect("a file address, not a bit");
        if (!op.address.indexed)
          warning(op.pos, where() + ": file operand written without '#'; RSLogix 500 writes #" + op.text());
        break;
      case OperandKind::Timer:
      case OperandKind::Counter:
      case OperandKind::Control:
      case OperandKind::Resettable: {
        FileType want = os.kind == OperandKind::Timer     ? FileType::Timer
                        : os.kind == OperandKind::Counter ? FileType::Counter
                                                          : FileType::Control;
        bool type_ok = op.is_address() && (os.kind == OperandKind::Resettable ? is_structured(op.address.type)
                                                                             : op.address.type == want);
        if (!type_ok || op.address.has_bit() || op.address.word > 0) return expect(to_string(os.kind));
        break;
      }
      case OperandKind::TimeBase:
        if (op.kind == Operand::Kind::Float && op.real == 0.001) {
          // The 0.001 s time base exists on the MicroLogix 1100-1500 only (1763-RM001, 1766-RM001,
          // 1762-RM001 "Timer Instructions": time base 0.001, 0.01 or 1.0 s).
          if (!program_.processor.has_millisecond_timebase())
            return error(op.pos, where() + ": the 0.001 s time base exists on the MicroLogix 1100, 1200, 1400 and 1500 "
                                         "only; " + program_.processor.display_name + " has 1.0 and 0.01");
          break;
        }
        if (!op.is_number() || !((op.kind == Operand::Kind::Float && (op.real == 1.0 || op.real == 0.01)) ||
                                 (op.kind == Operand::Kind::Integer && op.integer == 1)))
          return expect(program_.processor.has_millisecond_timebase() ? "time base 1.0, 0.01 or 0.001"
                                                                      : "time base 1.0 or 0.01");
        break;
      case OperandKind::Literal:
      case OperandKind::Label:
      case OperandKind::ProgramFile:
        if (op.kind != Operand::Kind::Integer) return expect("an integer constant");
        if (op.integer < os.min || op.integer > os.max)
          return error(op.pos, where() + " " + op.text() + " is out of range " + std::to_string(os.min) + "-" +
                                   std::to_string(os.max));
        break;
      case OperandKind::SlotWord: {
        FileType want = in.opcode == Opcode::IIM ? FileType::Input : FileType::Output;
        if (!op.is_address() || op.address.type != want || op.address.has_bit())
          return expect(want == FileType::Input ? "an input slot word such as I:1.0" : "an output slot word such as O:2.0");
        break;
      }
      case OperandKind::Buffer: {
        FileType want = in.opcode == Opcode::BTR ? FileType::M1 : FileType::M0;
        if (!op.is_address() || op.address.type != want || op.address.has_bit() || op.address.word % 100 != 0 ||
            op.address.word < 100 || op.address.word > 3200)
          return expect(std::string(want == FileType::M1 ? "M1" : "M0") +
                        ":e.x00 with buffer x = 1-32 (1747-SN manual p. 5-6)");
        break;
      }
      case OperandKind::Expression:
        // Only the CPT rule of the grammar makes an expression operand; check_cpt reads it.
        if (op.kind != Operand::Kind::Expression) return expect("a CPT expression");
        return;
      case OperandKind::String:
        // 1747-RM001G p. 10-3: string operands are ST elements (42 words, length in word 0).
        if (!op.is_address() || op.address.type != FileType::String || op.address.has_bit() || op.address.word > 0)
          return expect("a string element such as ST10:0 (1747-RM001 p. 10-3)");
        break;
      case OperandKind::ControlBlock3:
      case OperandKind::ControlBlock70:
      case OperandKind::ControlBlock23: {
        int len = os.kind == OperandKind::ControlBlock3 ? 3 : os.kind == OperandKind::ControlBlock23 ? 23 : 70;
        if (!op.is_address() || op.address.type != FileType::Integer || op.address.has_bit())
          return expect(os.kind == OperandKind::ControlBlock23
                            ? "an integer file element such as N10:0 (the PID control block is 23 words of an N file, "
                              "1747-RM001G p. 9-3)"
                            : "an integer file element such as N10:0");
        if (!op.address.indirect_element() && op.address.element + len > 256)
          return error(op.pos, where() + ": the " + std::to_string(len) + "-word control block starting at " +
                                   op.text() + " runs past the end of the file (element 255)");
        break;
      }
      // MSG (docs/semantics.md "MSG"): the keywords are checked by check_keyword, the lengths and the
      // target by check_message once every operand is known.
      case OperandKind::MessageCommand:
      case OperandKind::MessageDevice:
      case OperandKind::MessageRoute: return;
      case OperandKind::MessageBlock:
        if (!op.is_address() || op.address.type != FileType::Integer || op.address.has_bit() || op.address.word > 0 ||
            op.address.is_indirect() || op.address.indexed)
          return expect("an integer file element such as N9:0 (the MSG control block, 1747-RM001G p. 12-31)");
        break;
      case OperandKind::MessageData: {
        static constexpr FileType kTypes[] = {FileType::Output, FileType::Input, FileType::Status, FileType::Bit,
                                              FileType::Timer,  FileType::Counter, FileType::Control, FileType::Integer,
                                              FileType::Float,  FileType::String, FileType::Ascii};
        // A Modbus bit command's data is a bit address (check_modbus_message holds which take one).
        const bool modbus_bit = in.opcode == Opcode::MSG_ML && op.is_address() && op.address.bit >= 0 &&
                                !op.address.indirect_bit();
        if (!op.is_address() || (op.address.has_bit() && !modbus_bit) || op.address.is_indirect() || op.address.indexed ||
            std::find(std::begin(kTypes), std::end(kTypes), op.address.type) == std::end(kTypes) ||
            (is_structured(op.address.type) && op.address.word >= 0) ||
            (op.address.type == FileType::String && op.address.word > 0))
          return expect("a direct element address of an O, I, S, B, T, C, R, N, F, ST or A file such as N7:0 "
                        "(1747-RM001G p. 12-31, word 4)");
        break;
      }
      case OperandKind::RemoteAddress: return;  // the target's data table, not this program's
      case OperandKind::MessageElement:
        if (!op.is_address() || op.address.type != FileType::Message || op.address.word >= 0 || op.address.has_bit() ||
            op.address.is_indirect() || op.address.indexed)
          return expect("an MG file element such as MG11:0 (the MicroLogix MSG file, 1762-RM001C p. 21-4)");
        break;
      // A node number (range checked per channel by check_micrologix_message), or the RI element of a
      // channel 1 Ethernet message (1766-RM001A p. 435), a whole element the setup screen names.
      case OperandKind::MessageTarget:
        if (op.kind == Operand::Kind::Integer) {
          if (op.integer < os.min || op.integer > os.max)
            return error(op.pos, where() + " " + op.spelling + " is out of range " + std::to_string(os.min) + "-" +
                                     std::to_string(os.max));
          break;
        }
        if (!op.is_address() || op.address.type != FileType::Routing || op.address.word >= 0 || op.address.has_bit() ||
            op.address.is_indirect() || op.address.indexed)
          return expect("a target node number, or on channel 1 (Ethernet) an RI routing element such as RI12:0 "
                        "(1763-RM001B p. 384, 1766-RM001A p. 435)");
        break;
    }
    if (op.is_address()) check_address(op.address, op.pos, os.kind, os.mfile);
  }

  // HSL and RAC name their counter as RSLogix shows it, HSC0 to HSC5 (1762-RM001C p. 5-27: "Counter
  // HSC0"), or by its number: the name is read as the number, its spelling kept for the listing.
  static void name_hsc_counter(Operand& op) {
    if (op.kind != Operand::Kind::Symbol || op.spelling.size() != 4 || op.spelling.compare(0, 3, "HSC") != 0 ||
        op.spelling[3] < '0' || op.spelling[3] > '9')
      return;
    op.kind = Operand::Kind::Integer;
    op.integer = op.spelling[3] - '0';
  }

  // SVC's channel select names channels the controller has. The MicroLogix 1200 and the 1500 LSP
  // have one, channel 0: select 1 only (1762-RM001C p. 21-27, the channel-select table); the 1500
  // LRP takes 1, 2 or 3 (the same table), the 1100 and 1400 channel 0, channel 1 or both (the rows
  // of their execution-time tables, 1763-RM001B p. 344, 1766-RM001A p. 396). The SLC 5/03-5/05 form
  // takes bits 0 and 1 (the table's 1-3).
  void check_channel_select(const Operand& select) {
    const auto m = program_.processor.micrologix;
    if ((m == MicroLogixModel::ML1200 || m == MicroLogixModel::ML1500LSP) && select.integer != 1)
      error(select.pos, "SVC channel select " + select.text() + ": the " + program_.processor.display_name +
                            " has one channel, channel 0: its channel select is 1 (1762-RM001C p. 21-27)");
  }

  // The form an instruction is held to. The loader takes the form whose operand count was written,
  // or the mnemonic's first row when no form has that count; then, when the processor lacks that
  // first row but has another form of the mnemonic (MSG on a MicroLogix, OSR on an SLC ...), the
  // processor's own form is the one whose operands the messages should list.
  const InstructionSpec& form_to_check(const Instruction& in) const {
    const InstructionSpec& written = spec(in.opcode);
    const auto& proc = program_.processor;
    if (in.operands.size() == written.operand_count || proc.supports(written.requires_)) return written;
    for (const InstructionSpec& row : kInstructionTable)
      if (row.mnemonic == written.mnemonic && proc.supports(row.requires_)) return row;
    return written;
  }

  void check_instruction(Instruction& in, bool first_in_rung, int file_number, int rung_index) {
    const auto& s = form_to_check(in);
    auto& proc = program_.processor;
    if (!proc.supports(s.requires_)) error(in.pos, mnemonic_of(in) + " " + proc.requirement_text(s.requires_));
    if (in.operands.size() != s.operand_count) {
      // A surplus operand that is an unknown name was most likely meant as a mnemonic.
      if (in.operands.size() > s.operand_count) {
        auto& extra = in.operands[s.operand_count];
        if (extra.kind == Operand::Kind::Symbol && !symbols_.count(extra.spelling)) {
          error(extra.pos, unknown_instruction_message(extra.spelling));
          unknown_in_rung_ = true;
          return;
        }
      }
      std::string labels;
      for (const auto& o : s.operand_specs()) labels += (labels.empty() ? "" : ", ") + std::string(o.label);
      error(in.pos, mnemonic_of(in) + " takes " + std::to_string(s.operand_count) + " operand" +
                        (s.operand_count == 1 ? "" : "s") + (labels.empty() ? "" : " (" + labels + ")") + ", found " +
                        std::to_string(in.operands.size()));
      return;
    }
    if (in.opcode == Opcode::HSL || in.opcode == Opcode::RAC) name_hsc_counter(in.operands[0]);
    for (std::size_t i = 0; i < in.operands.size(); ++i) check_operand(in, in.operands[i], s.operands[i]);
    if ((in.opcode == Opcode::HSL || in.opcode == Opcode::RAC) && in.operands[0].kind == Operand::Kind::Integer &&
        in.operands[0].integer >= 0 && in.operands[0].integer < 6 && in.operands[0].integer >= proc.hsc_count() &&
        proc.supports(s.requires_))
      error(in.operands[0].pos, mnemonic_of(in) + " counter " + in.operands[0].text() + ": the " + proc.display_name +
                                    " has " + std::to_string(proc.hsc_count()) + " high-speed counter(s) (1762-RM001C p. 5-27; "
                                    "docs/semantics.md \"The HSC function file\")");
    if (in.opcode == Opcode::SVC_CH && in.operands[0].kind == Operand::Kind::Integer && proc.supports(s.requires_))
      check_channel_select(in.operands[0]);
    // "You must configure a data log queue before programming a DLG instruction" (AG-UM008C p. 3-64).
    if (in.opcode == Opcode::DLG && in.operands[0].kind == Operand::Kind::Integer && proc.supports(s.requires_) &&
        !program_.find_data_log(static_cast<int>(in.operands[0].integer)))
      error(in.operands[0].pos, "DLG " + in.operands[0].text() + ": data log queue " + in.operands[0].text() +
                                    " is not configured (a queue must be configured before a DLG names it, AG-UM008C "
                                    "p. 3-64); add DATALOG " + in.operands[0].text() + " RECORDS n DELIMITER COMMA <fields>");
    if (s.role == Role::Leading && !first_in_rung)
      error(in.pos, mnemonic_of(in) + " must be the first instruction of its rung");
    if (in.opcode == Opcode::SBR && (file_number < 3 || rung_index != 0))
      error(in.pos, "SBR belongs at the start of the first rung of a subroutine file (3-255)");
    const bool one_shot = in.opcode == Opcode::OSR || in.opcode == Opcode::ONS || in.opcode == Opcode::OSR_ML ||
                          in.opcode == Opcode::OSF;
    if (one_shot && !in.operands.empty() && in.operands[0].is_address()) {
      const auto& a = in.operands[0].address;
      if (a.type != FileType::Bit && a.type != FileType::Integer && !is_mfile(a.type))
        error(in.operands[0].pos, "the " + mnemonic_of(in) + " storage bit must be in a B or N file");
      osr_bits_.emplace_back(a, in.operands[0].pos);
    }
    // JSR's file, and the STI file STS names (RM 11-16), must be program files of this program.
    if ((in.opcode == Opcode::JSR || in.opcode == Opcode::STS) && in.operands.size() == s.operand_count &&
        in.operands[0].kind == Operand::Kind::Integer)
      (in.opcode == Opcode::JSR ? jsr_targets_ : sts_targets_)
          .emplace_back(static_cast<int>(in.operands[0].integer), in.operands[0].pos);
    if (in.opcode == Opcode::STS_ML) ml_sts_uses_.push_back(in.pos);
    if (in.opcode == Opcode::INT && (file_number < 3 || rung_index != 0))
      error(in.pos, "INT belongs at the start of the first rung of an interrupt subroutine file (3-255)");
    if (in.opcode == Opcode::CPT && in.operands.size() == 2 && in.operands[1].kind == Operand::Kind::Expression)
      check_cpt(in);
    if (in.opcode == Opcode::SWP && in.operands.size() == 2 && in.operands[0].is_address() &&
        in.operands[1].kind == Operand::Kind::Integer)
      check_swap(in);
    if ((in.opcode == Opcode::RHC || in.opcode == Opcode::TDF) && in.operands.size() == s.operand_count)
      check_clock_operands(in);
    // RPC copies the checksum "into the designated destination integer file location" (1747-RM001G
    // p. 7-23, 1766-RM001A p. 239): an N word.
    if (in.opcode == Opcode::RPC && in.operands.size() == s.operand_count && in.operands[1].is_address() &&
        in.operands[1].address.type != FileType::Integer)
      error(in.operands[1].pos, "RPC writes its checksum to an N word (1747-RM001G p. 7-23), not " +
                                    in.operands[1].text());
    if (in.opcode == Opcode::PID && in.operands.size() == 3) check_pid(in);
    if ((in.opcode == Opcode::IID || in.opcode == Opcode::IIE || in.opcode == Opcode::RPI) &&
        in.operands.size() == 1 && in.operands[0].kind == Operand::Kind::Integer && (in.operands[0].integer & 1))
      error(in.operands[0].pos, mnemonic_of(in) + " slots: bit 0 is reserved (slot 0 is the processor); bit n of the "
                                "mask is slot n, 1-30 (1747-RM001G p. 11-31)");
    if ((in.opcode == Opcode::FBC || in.opcode == Opcode::DDT) && in.operands.size() == s.operand_count)
      check_bit_compare(in);
    if (in.operands.size() == s.operand_count) check_ascii_operands(in);
    if ((in.opcode == Opcode::MSG || in.opcode == Opcode::MSG_502) && in.operands.size() == s.operand_count &&
        proc.supports(s.requires_))
      check_message(in);
    if (in.opcode == Opcode::MSG_ML && in.operands.size() == s.operand_count && proc.supports(s.requires_))
      check_micrologix_message(in);
  }

  // FBC, DDT (1747-RM001G p. 7-18 .. 7-22): the result file records bit numbers, so it is
  // an integer file; the compare and result control elements must differ (each keeps its own LEN and
  // POS, table 7.8).
  void check_bit_compare(const Instruction& in) {
    const Operand& result = in.operands[2];
    if (result.is_address() && result.address.type != FileType::Integer && !result.address.indirect_file())
      error(result.pos, mnemonic_of(in) + " result must be an integer (N) file: it holds the numbers of the "
                        "mismatched bits (1747-RM001G p. 7-18)");
    const Operand& cmp = in.operands[3];
    const Operand& res = in.operands[6];
    if (cmp.is_address() && res.is_address() && !cmp.address.is_indirect() && !res.address.is_indirect() &&
        cmp.address.file == res.address.file && cmp.address.element == res.address.element)
      error(res.pos, mnemonic_of(in) + " needs two control elements: the compare and the result control are both " +
                         to_string(cmp.address));
  }

  // ASCII and string instructions (1747-RM001G ch. 10). AEX's index and number and ASC's index are
  // 1-82 (RM 10-12); a constant outside that would only set S:5/15 at run time, so check says so now.
  // ACI, AIC and ASC's result are 16-bit words: the MicroLogix long-word forms (an L operand) are not
  // simulated.
  void check_ascii_operands(const Instruction& in) {
    auto in_1_82 = [&](std::size_t i, std::string_view what) {
      const Operand& op = in.operands[i];
      if (op.kind == Operand::Kind::Integer && (op.integer < 1 || op.integer > 82))
        error(op.pos, mnemonic_of(in) + " " + std::string(what) + " " + op.text() +
                          " is out of range 1-82 (1747-RM001 p. 10-12)");
    };
    auto not_long = [&](std::size_t i) {
      const Operand& op = in.operands[i];
      if (op.is_address() && op.address.type == FileType::Long)
        error(op.pos, mnemonic_of(in) + " with an L word is the MicroLogix long-word form, which softslc does not "
                                        "simulate yet; use an N word");
    };
    switch (in.opcode) {
      case Opcode::AEX: in_1_82(1, "index"); in_1_82(2, "number"); break;
      case Opcode::ASC: in_1_82(1, "index"); not_long(3); break;
      case Opcode::ACI: not_long(1); break;
      case Opcode::AIC: not_long(0); break;
      default: break;
    }
  }

  // READ/WRITE, 500CPU/485CIF/PLC5, LOCAL/REMOTE: words of the MSG box (RM 12-5), never symbols.
  void check_keyword(const Instruction& in, const Operand& op, const OperandSpec& os) {
    // A MicroLogix Modbus MSG names its Modbus command where the others say READ or WRITE: check_modbus_message.
    if (os.kind == OperandKind::MessageCommand && in.opcode == Opcode::MSG_ML && op.kind == Operand::Kind::Integer) return;
    if (os.kind == OperandKind::MessageDevice && in.opcode != Opcode::MSG_ML && op.kind == Operand::Kind::Symbol &&
        op.spelling == "MODBUS")
      return error(op.pos, "MSG MODBUS is the MicroLogix 1100/1400 form (MSG MG11:0 03 MODBUS LOCAL 0 ...); the "
                           "SLC 5/03-5/05's Modbus RTU master on channel 0 (1747-RM001G p. 12-35) is not simulated "
                           "by softslc, nor has the MicroLogix 1000 one");
    std::string choices;
    for (auto w : keyword_words(os.kind)) choices += (choices.empty() ? "" : ", ") + std::string(w);
    if (op.kind != Operand::Kind::Symbol || !keyword_code(os.kind, op.spelling))
      error(op.pos, mnemonic_of(in) + " " + std::string(os.label) + ": expected " + choices + ", found '" +
                        op.text() + "'");
  }

  // The Ethernet block's setup that a DATA block gives it (RM 12-34 table 12.14): word 35 = 10h or 11h is a
  // MultiHop message and AO (word 12 bit 15) with PLC5 logical ASCII addressing; softslc simulates neither,
  // so they are refused here rather than left to end the message with 17h at run time.
  void check_ethernet_block_data(const Operand& block, bool plc5) {
    for (const DataBlock& d : program_.data) {
      if (d.type != FileType::Integer || d.file != block.address.file) continue;
      auto value = [&](int word) -> std::optional<std::int64_t> {
        const int i = block.address.element + word - d.start_element;
        if (i < 0 || static_cast<std::size_t>(i) >= d.words.size()) return std::nullopt;
        return d.words[static_cast<std::size_t>(i)];
      };
      if (auto type = value(kEthernetMessageTypeWord); type && is_multihop_message_type(static_cast<std::uint16_t>(*type)))
        error(block.pos, "MSG control block " + block.text() + ": word 35 (set by the DATA block at line " +
                             std::to_string(d.pos.line) + ") makes it a MultiHop message (1747-RM001G p. 12-34 "
                             "table 12.14), which softslc does not simulate; the simulated Ethernet is one network "
                             "of SLC 5/05s reached by IP address (word 35 = 0)");
      if (auto ao = value(kMessageAoWord); plc5 && ao && (*ao & kMessageAoBit))
        error(block.pos, "MSG control block " + block.text() + ": AO (word 12 bit 15, set by the DATA block at line " +
                             std::to_string(d.pos.line) + ") selects PLC5 logical ASCII addressing (1747-10.4 p. 4-3), "
                             "which softslc does not simulate");
    }
  }

  // MSG (1747-RM001G ch. 12, ch. 13; docs/semantics.md "MSG"): what the processor's channel can send,
  // the target node's range on its link, a control block and a data table range inside their files,
  // the target address, and one control block per MSG.
  void check_message(const Instruction& in) {
    const bool slc502 = in.opcode == Opcode::MSG_502;
    const auto& ops = in.operands;
    const Operand& command = ops[0];
    const Operand& device = ops[1];
    const Operand& block = ops[slc502 ? 2 : 3];
    const Operand& block_length = ops[slc502 ? 3 : 4];
    const Operand& data = ops[slc502 ? 4 : 6];
    const Operand& size = ops[slc502 ? 5 : 7];
    const Operand& node = ops[slc502 ? 6 : 8];
    const Operand& target = ops[slc502 ? 7 : 9];
    if (!slc502 && ops[2].kind == Operand::Kind::Symbol && ops[2].spelling == "REMOTE")
      return error(ops[2].pos, "MSG REMOTE (a message through a bridge to another link, 1747-RM001G p. 15-2) is not "
                               "simulated by softslc; the simulated network is one link: use LOCAL");
    const auto& proc = program_.processor;
    const int channel = slc502 ? 0 : static_cast<int>(ops[5].integer);
    const MessageLink link = message_link(proc.family, channel);
    if (link == MessageLink::None)
      return error(ops[5].pos, "MSG on channel " + std::to_string(channel) + ": the " + std::string(proc.display_name) +
                                   " has no such channel (1747-RM001G p. 12-14)");
    const bool ethernet = link == MessageLink::Ethernet;
    const bool ml1000 = proc.micrologix == MicroLogixModel::ML1000;
    const std::string dev = device.kind == Operand::Kind::Symbol ? device.spelling : "";
    if (dev == "PLC5" && ml1000)
      return error(device.pos, "MSG PLC5: the MicroLogix 1000's command types are SLC500/ML1000 (500CPU) and CIF "
                               "(485CIF), and it reaches a PLC-5 only with CIF over DF1 full-duplex (1761-6.2 p. "
                               "15-3), which softslc does not simulate (docs/semantics.md \"The MicroLogix 1000 "
                               "MSG\")");
    if (dev == "PLC5" && link == MessageLink::Dh485)
      return error(device.pos, "MSG PLC5 on DH-485: a PLC-5 is on DH+ or Ethernet; the " + proc.display_name +
                                   "'s DH-485 channel sends 500CPU and 485CIF messages (docs/semantics.md \"MSG\")");
    // Channel 0 of the 5/03-5/05 is DF1 full-duplex when a MSG uses it (the only System-mode link softslc
    // simulates there; docs/semantics.md "DF1 full-duplex on channel 0"): its far end is an SLC or a
    // MicroLogix, and the PLC-5 typed commands' packets are not built.
    if (dev == "PLC5" && link == MessageLink::Df1)
      return error(device.pos, "MSG PLC5 on channel 0 (DF1 full-duplex): softslc's DF1 peers are SLC and MicroLogix "
                               "controllers, reached with 500CPU or 485CIF; the PLC-5 typed read and write are not "
                               "simulated (docs/semantics.md \"DF1 full-duplex on channel 0\")");
    // The control block: 7 words (SLC 5/02), 14 (DH-485, DH+) or 51 (the SLC 5/05's Ethernet channel, RM
    // 12-34 table 12.14) of one N file.
    const int blen = static_cast<int>(block_length.integer);
    const int expected = slc502 ? 7 : ethernet ? kEthernetMessageBlockWords : 14;
    if (block_length.kind == Operand::Kind::Integer && blen != expected) {
      if (ethernet && blen == 93)
        return error(block_length.pos, "the 93-word MSG control block is the SLC 5/05's logical ASCII addressing "
                                       "form (AO=1, PLC5 only, 1747-RM001G p. 12-36 table 12.16), which softslc does "
                                       "not simulate; use the 51-word block of table 12.14");
      return error(block_length.pos,
                   "MSG on " + std::string(to_string(link)) + " (channel " + std::to_string(channel) + " of the " +
                       proc.display_name + ") takes a " + std::to_string(expected) + "-word control block, not " +
                       block_length.text() +
                       (ethernet ? " (1747-RM001G p. 12-34 table 12.14)"
                        : blen == kEthernetMessageBlockWords ? " (51 words is the SLC 5/05's Ethernet block)"
                        : ml1000                            ? " (1761-6.3 p. 13-13: \"Control Block Length 7\")"
                                                            : " (1747-RM001G p. 12-31)"));
    }
    if (node.kind == Operand::Kind::Integer) {
      // A MicroLogix's channel 0 is DH-485 or DF1 full-duplex by its channel configuration, which is not in
      // the program: its node is a DF1 station address, 0-254, and on DH-485 a node above 31 ends the
      // message at run time (16h; the 1000: no response, 07h).
      const auto [lo, hi] = proc.is_micrologix() && channel == 0 ? message_node_range(MessageLink::Df1)
                                                                 : message_node_range(link);
      if (ethernet && node.integer != 0)
        error(node.pos, "MSG on Ethernet has no target node: the target is the IP address string in words 14-34 of "
                        "the control block (1747-RM001G p. 12-34 table 12.14); write 0 for the node");
      else if (!ethernet && (node.integer < lo || node.integer > hi))
        error(node.pos, "MSG target node " + node.text() + " is out of range " + std::to_string(lo) + "-" +
                            std::to_string(hi) + " for " + std::string(to_string(link)) +
                            (proc.is_micrologix() && channel == 0
                                 ? " on channel 0 (DF1 station addresses 0-254, 1766-RM001A p. 592; DH-485 "
                                   "responders are 1-31)"
                             : link == MessageLink::Dh485 ? " (1747-RM001G p. 13-4: responders 1-31; node 0 is a "
                                                            "programming device)"
                             : link == MessageLink::Df1 ? " (DF1 station addresses 0-254; the receiver ignores the "
                                                          "destination, 1747-RM001G p. 13-49)"
                                                        : " (DH+ node addresses 0-77 octal)"));
    }
    if (block.is_address() && block.address.element + blen > 256)
      error(block.pos, "the " + std::to_string(blen) + "-word MSG control block starting at " + block.text() +
                           " does not fit its file (it would end past element 255; 1747-RM001G p. " +
                           (ethernet ? "12-34)" : "12-31)"));
    if (block.is_address()) {
      const int first = block.address.element, last = block.address.element + blen - 1;
      if (const int line = claim_message_state(block.address.file, first, last, block.pos))
        error(block.pos, "MSG control block " + block.text() + " overlaps the one of the MSG at line " +
                             std::to_string(line) + "; every MSG needs its own control block (1747-RM001G p. 12-30)");
      if (ethernet) check_ethernet_block_data(block, dev == "PLC5");
    }
    check_message_data(command, dev, data, size, target, ethernet);
  }

  // Records that the MSG at `pos` keeps its state in elements first..last of `file` (an SLC control
  // block, a MicroLogix MG element); returns the line of an earlier MSG whose state overlaps them, or 0.
  int claim_message_state(int file, int first, int last, SourcePos pos) {
    int line = 0;
    for (const auto& [f, other_first, other_last, other_pos] : message_blocks_)
      if (f == file && first <= other_last && other_first <= last) {
        line = other_pos.line;
        break;
      }
    message_blocks_.push_back({file, first, last, pos});
    return line;
  }

  // The data of a MSG, either form: `size` elements of the local file, inside the file and one message;
  // the target, a data table address of the other controller (500CPU, PLC5) of the local file's type, or
  // a word offset into its common interface file (485CIF).
  void check_message_data(const Operand& command, const std::string& dev, const Operand& data, const Operand& size,
                          const Operand& target, bool ethernet) {
    if (data.is_address() && size.kind == Operand::Kind::Integer) {
      const int wpe = words_per_element(data.address.type);
      if (data.address.element + size.integer > 256)
        error(size.pos, "MSG of " + size.text() + " element(s) from " + data.text() +
                            " runs past the end of the file (element 255)");
      else if (ethernet) {
        const int most = ethernet_max_elements(data.address.type, dev == "PLC5", command.kind == Operand::Kind::Symbol &&
                                                                                   command.spelling == "WRITE");
        if (size.integer > most)
          error(size.pos, "MSG of " + size.text() + " " + std::string(file_letter(data.address.type)) +
                              " element(s): one message on the SLC 5/05's Ethernet channel carries at most " +
                              std::to_string(most) + " (1747-RM001G p. D-21 table D.5)");
      } else if (size.integer * wpe > kMessageMaxWords)
        error(size.pos, "MSG of " + size.text() + " " + std::string(file_letter(data.address.type)) +
                            " element(s) is " + std::to_string(size.integer * wpe) + " words; one message carries at "
                            "most " + std::to_string(kMessageMaxWords) + " (docs/semantics.md \"MSG\")");
    }
    if (dev == "485CIF") {
      if (target.kind != Operand::Kind::Integer || target.integer < 0 || target.integer > 255)
        error(target.pos, "MSG 485CIF target: expected a word offset 0-255 into the target's common interface file "
                          "(1763-RM001 \"Data Table Address/Offset\"), found '" + target.text() + "'");
      return;
    }
    if (target.kind != Operand::Kind::Address)
      return error(target.pos, "MSG target address: expected the target controller's data table address such as "
                               "N7:0 (written as an address: a SYMBOL names this program's data), found '" +
                                   target.text() + "'");
    const Address& t = target.address;
    if (t.has_bit() || t.is_indirect() || t.indexed || is_mfile(t.type) || is_function_file(t.type) ||
        (is_structured(t.type) && t.word >= 0) || (t.type == FileType::String && t.word > 0))
      return error(target.pos, "MSG target address: expected a direct element address such as N7:0, found '" +
                                   target.text() + "'");
    if (data.is_address() && t.type != data.address.type)
      error(target.pos, "MSG target " + target.text() + " is not of the local data's file type (" +
                            std::string(file_letter(data.address.type)) + "); the control block carries one file type "
                            "for both (1747-RM001G p. 12-31, word 4)");
    if (size.kind == Operand::Kind::Integer && t.element + size.integer > 256)
      error(size.pos, "MSG of " + size.text() + " element(s) to " + target.text() +
                          " runs past the end of any file (element 255)");
  }

  // The MicroLogix 1100-1500 MSG (docs/semantics.md "The MicroLogix MSG"): the MG element, one per MSG
  // (1762-RM001C p. 21-4: "Each MSG instruction must use a unique Element in a MSG File"); channel 0, the
  // controller's serial port, on the simulated DH-485 link; the node, data and target as the SLC form's.
  void check_micrologix_message(const Instruction& in) {
    const auto& ops = in.operands;
    const Operand& element = ops[0];
    const Operand& device = ops[2];
    const Operand& channel = ops[4];
    const Operand& node = ops[7];
    const auto& proc = program_.processor;
    if (device.kind == Operand::Kind::Symbol && device.spelling == "MODBUS") return check_modbus_message(in);
    if (ops[1].kind == Operand::Kind::Integer)
      return error(ops[1].pos, "MSG command " + ops[1].spelling + ": a Modbus command (01-06, 15, 16) goes with target "
                               "device MODBUS; a " + (device.kind == Operand::Kind::Symbol ? device.spelling : "PCCC") +
                               " message is READ or WRITE");
    if (ops[5].is_address() && ops[5].address.has_bit())
      return error(ops[5].pos, "MSG data table address " + ops[5].text() + " is a bit: a bit address is the data of a "
                               "Modbus coil or input command only (01, 02, 05, 15); this message moves elements from "
                               "a word address such as N7:0");
    if (ops[3].kind == Operand::Kind::Symbol && ops[3].spelling == "REMOTE")
      return error(ops[3].pos, "MSG REMOTE (a message through a bridge to another link, 1762-RM001C p. 21-13) is not "
                               "simulated by softslc; the simulated network is one link: use LOCAL");
    // Channel 1: the 1100/1400's Ethernet port; the 1764-LRP's second serial port, on DH-485 as channel 0
    // is ("For controllers with 2 channels (1764-LRP processor installed), the channel can be 0 or 1",
    // 1762-RM001C p. 21-12), so the channel 0 rules below hold for it; one channel elsewhere.
    if (channel.kind == Operand::Kind::Integer && channel.integer == 1) {
      if (proc.has_routing_files()) return check_micrologix_ethernet_message(in);
      if (proc.micrologix != MicroLogixModel::ML1500LRP)
        return error(channel.pos, "the " + proc.display_name + " has one channel: its MSG channel is always 0 "
                                  "(1762-RM001C p. 21-4, sub-element 8)");
    }
    const std::string port = channel.kind == Operand::Kind::Integer ? std::to_string(channel.integer) : "0";
    if (node.is_address())
      return error(node.pos, "MSG target " + node.text() + ": an RI routing element is for a channel 1 Ethernet "
                             "message of the MicroLogix 1100/1400 (1763-RM001B p. 384, 1766-RM001A p. 435); on the " +
                             proc.display_name + "'s channel " + port + " (DH-485) the target is a node number, 1-31");
    const std::string dev = device.kind == Operand::Kind::Symbol ? device.spelling : "";
    if (dev == "PLC5")
      return error(device.pos, "MSG PLC5 on DH-485: a PLC-5 is on DH+ or Ethernet; the " + proc.display_name +
                                   "'s channel " + port + " on the simulated DH-485 link sends 500CPU and 485CIF messages, "
                                   "as on a DF1 full-duplex channel 0, whose simulated peers are SLC and MicroLogix "
                                   "controllers (docs/semantics.md \"MSG\")");
    if (node.kind == Operand::Kind::Integer) {
      // Channel 0 is DH-485 or DF1 full-duplex by the channel configuration, which is not in the program: a DF1
      // station address, 0-254 (1766-RM001A p. 592); on DH-485 a node above 31 ends the message with 16h at run
      // time. The 1764-LRP's channel 1 is DH-485 only.
      const bool serial0 = port == "0";
      const auto [lo, hi] = message_node_range(serial0 ? MessageLink::Df1 : MessageLink::Dh485);
      if (node.integer < lo || node.integer > hi)
        error(node.pos, "MSG target node " + node.text() + " is out of range " + std::to_string(lo) + "-" +
                            std::to_string(hi) +
                            (serial0 ? " on channel 0 (DF1 station addresses 0-254, 1766-RM001A p. 592; DH-485 "
                                       "responders are 1-31)"
                                     : " for DH-485 (1747-RM001G p. 13-4: responders 1-31)"));
    }
    claim_message_element(element);
    const Operand& data = ops[5];
    if (long_message_data(data)) return;
    check_message_data(ops[1], dev, data, ops[6], ops[8], false);
  }
  // The MicroLogix 1100/1400 Modbus RTU master MSG (docs/semantics.md "The MicroLogix MSG over Modbus RTU"):
  //   MSG MG11:0 <command 01-06, 15, 16> MODBUS LOCAL 0 <data> <size> <slave 0-247> <Modbus address 1-65536> <timeout>
  // The eight commands of 1763-RM001B p. 366; the slave address and the 1-based data address of the setup screen
  // (1747-RM001G p. 12-22, the same screen: "MB Data Address (1-65536)"); B and N data only, a bit address for the
  // coil and input commands, a word address for the register commands (1747-RM001G p. 12-18: the MicroLogix
  // page was not reached [U]).
  void check_modbus_message(const Instruction& in) {
    const auto& ops = in.operands;
    const Operand& command = ops[1];
    const Operand& device = ops[2];
    const Operand& data = ops[5];
    const Operand& size = ops[6];
    const Operand& slave = ops[7];
    const Operand& target = ops[8];
    const auto& proc = program_.processor;
    if (!proc.has_routing_files())
      return error(device.pos, "MSG MODBUS: the " + proc.display_name + " has no Modbus RTU master MSG; MG sub-element 2 "
                               "(the messaging type, 2 = Modbus master on the 1100 and 1400, 1763-RM001B p. 347) is "
                               "reserved on the MicroLogix 1200 and 1500 (1762-RM001C p. 21-4)");
    if (command.kind != Operand::Kind::Integer || !modbus::is_command(static_cast<int>(command.integer)))
      return error(command.pos, "MSG MODBUS command '" + command.text() + "': expected a Modbus command, 01 Read Coil "
                                "Status, 02 Read Input Status, 03 Read Holding Registers, 04 Read Input Registers, 05 "
                                "Write Single Coil, 06 Write Single Register, 15 Write Multiple Coils or 16 Write "
                                "Multiple Registers (1763-RM001B p. 366)");
    const int f = static_cast<int>(command.integer);
    if (ops[3].kind != Operand::Kind::Symbol || ops[3].spelling != "LOCAL")
      return error(ops[3].pos, "MSG MODBUS is LOCAL: a Modbus message goes to a slave on the channel's own line");
    if (ops[4].kind == Operand::Kind::Integer && ops[4].integer != 0)
      return error(ops[4].pos, "MSG MODBUS on channel " + ops[4].spelling + ": the Modbus RTU master is channel 0, the "
                               "serial port (channel 1 of the " + proc.display_name + " is Ethernet)");
    claim_message_element(ops[0]);
    const bool bits = modbus::is_bit_command(f);
    if (data.is_address()) {
      const FileType t = data.address.type;
      if (t != FileType::Bit && t != FileType::Integer)
        error(data.pos, "MSG MODBUS data " + data.text() + ": only B and N files are valid for Modbus command messages "
                        "(1747-RM001G p. 12-18)");
      else if (bits && !data.address.has_bit())
        error(data.pos, "MSG MODBUS " + command.spelling + " moves bits (coils or inputs): its data table address is a "
                        "bit address such as " + data.text() + "/0 (1747-RM001G p. 12-18)");
      else if (!bits && data.address.has_bit())
        error(data.pos, "MSG MODBUS " + command.spelling + " moves registers: its data table address is a word address "
                        "such as " + std::string(file_letter(t)) + std::to_string(data.address.file) + ":" +
                        std::to_string(data.address.element) + ", not the bit " + data.text() + " (1747-RM001G p. 12-18)");
    }
    if (modbus::is_single_command(f) && size.kind == Operand::Kind::Integer && size.integer != 1)
      error(size.pos, "MSG MODBUS " + command.spelling + " writes one " + (bits ? "coil" : "register") + ": its size in "
                      "elements is 1 (1763-RM001B p. 366: \"writing 1 " + (bits ? "bit" : "word") + "\")");
    if (slave.kind != Operand::Kind::Integer)
      return error(slave.pos, "MSG MODBUS target " + slave.text() + ": the target is the slave address, 1-247 (0: a "
                              "broadcast write)");
    if (slave.integer > modbus::kMaxSlave)
      error(slave.pos, "MSG MODBUS slave address " + slave.spelling + " is out of range 1-247 (0: a broadcast write)");
    else if (slave.integer == 0 && !modbus::is_write_command(f))
      error(slave.pos, "MSG MODBUS slave address 0 is a broadcast, which only a write command (05, 06, 15, 16) can "
                       "send: no slave answers a broadcast");
    if (target.kind != Operand::Kind::Integer || target.integer < 1 || target.integer > 65536)
      return error(target.pos, "MSG MODBUS target address " + target.text() + ": expected the Modbus data address, "
                               "1-65536, without its 0x/1x/3x/4x prefix (1747-RM001G p. 12-22)");
    if (size.kind == Operand::Kind::Integer && target.integer + size.integer - 1 > 65536)
      error(target.pos, "MSG MODBUS " + size.spelling + " elements from Modbus address " + target.spelling +
                        " run past 65536, the end of the Modbus address space");
  }

  // "Each MSG instruction must use a unique Element in a MSG File" (1762-RM001C p. 21-4).
  void claim_message_element(const Operand& element) {
    if (!element.is_address()) return;
    const int e = element.address.element;
    if (const int line = claim_message_state(element.address.file, e, e, element.pos))
      error(element.pos, "MSG element " + element.text() + " is also the one of the MSG at line " +
                             std::to_string(line) + "; each MSG instruction must use a unique element in a MSG "
                             "file (1762-RM001C p. 21-4)");
  }

  // L data is refused on either channel: the PCCC type code a MicroLogix sends for L is not in the sources.
  bool long_message_data(const Operand& data) {
    if (!data.is_address() || data.address.type != FileType::Long) return false;
    error(data.pos, "MSG of L (long word) elements is not simulated by softslc: the file type code a "
                    "MicroLogix sends for L is not in its sources (docs/semantics.md \"The MicroLogix MSG\")");
    return true;
  }

  // The MicroLogix 1100/1400 MSG on channel 1, the embedded Ethernet port (docs/semantics.md "The MicroLogix
  // MSG on Ethernet"): the setup screen names the message's RI routing element where channel 0 names the
  // node (1763-RM001B p. 384, 1766-RM001A p. 435); the 1400 assigns the timeout itself (1766-RM001A p. 421);
  // 103 words a message as on channel 0 (AG-UM008C p. 3-38).
  void check_micrologix_ethernet_message(const Instruction& in) {
    const auto& ops = in.operands;
    const Operand& element = ops[0];
    const Operand& node = ops[7];
    const Operand& timeout = ops[9];
    const auto& proc = program_.processor;
    if (!node.is_address())
      return error(node.pos, "MSG on channel 1 (the " + proc.display_name + "'s Ethernet port) names its RI routing "
                             "element where channel 0 names the target node, e.g. RI12:0; its words 1-2 hold the "
                             "target's IP address (1763-RM001B p. 384, 1766-RM001A p. 435)");
    if (proc.micrologix == MicroLogixModel::ML1400 && timeout.kind == Operand::Kind::Integer &&
        timeout.integer != kMl1400EthernetMessageTimeoutSeconds)
      error(timeout.pos, "MSG message timeout " + timeout.spelling + ": the MicroLogix 1400 assigns a channel 1 MSG's "
                         "timeout itself, the channel's MSG Connection Timeout plus its MSG Reply Timeout plus 15 s "
                         "(1766-RM001A p. 421): " + std::to_string(kMl1400EthernetMessageTimeoutSeconds) +
                         " s with the defaults softslc simulates (15 s and 3 s); write " +
                         std::to_string(kMl1400EthernetMessageTimeoutSeconds));
    claim_message_element(element);
    // "Each channel 1 Ethernet MSG names its own RI element" (RSLogix creates one per MSG when the rung is
    // verified, 1766-RM001A p. 435); two MSGs sharing one still read the same address: a warning.
    const auto shared = std::find_if(routing_elements_.begin(), routing_elements_.end(), [&](const RoutingUse& r) {
      return r.file == node.address.file && r.element == node.address.element;
    });
    if (shared != routing_elements_.end())
      warning(node.pos, "MSG routing element " + node.text() + " is also the one of the MSG at line " +
                            std::to_string(shared->pos.line) + "; each channel 1 MSG has its own RI element "
                            "(1766-RM001A p. 435)");
    else
      routing_elements_.push_back({node.address.file, node.address.element, node.pos});
    check_routing_data(node);
    const Operand& data = ops[5];
    if (long_message_data(data)) return;
    const std::string dev = ops[2].kind == Operand::Kind::Symbol ? ops[2].spelling : "";
    check_message_data(ops[1], dev, data, ops[6], ops[8], false);
  }

  // An RI element a DATA block sets up (1766-RM001A p. 435): subtype 10h, a message to the IP address in
  // words 1-2; 11h (remote MultiHop to DH+ through a bridge) is not simulated, and any other subtype names
  // no routing. The network ends such messages with 17h and 21h; check says so where the DATA block is.
  void check_routing_data(const Operand& ri) {
    for (const DataBlock& d : program_.data) {
      if (d.type != FileType::Routing || d.file != ri.address.file) continue;
      const long i = static_cast<long>(ri.address.element - d.start_element) * ri::kWords + ri::kSubtype;
      if (i < 0 || static_cast<std::size_t>(i) >= d.words.size()) continue;
      const auto subtype = static_cast<std::uint16_t>(d.words[static_cast<std::size_t>(i)]);
      if (subtype == kRoutingRemoteDhPlus)
        error(ri.pos, "MSG routing element " + ri.text() + ": subtype 11h (set by the DATA block at line " +
                          std::to_string(d.pos.line) + ") is a remote MultiHop to DH+ (1766-RM001A p. 435), which "
                          "softslc does not simulate; a message to the IP address in words 1-2 has subtype 10h");
      else if (subtype != kRoutingLocal)
        error(ri.pos, "MSG routing element " + ri.text() + ": subtype " + std::to_string(subtype) +
                          " (set by the DATA block at line " + std::to_string(d.pos.line) + ") is neither 10h (16, "
                          "a message to the IP address in words 1-2) nor 11h (1766-RM001A p. 435)");
    }
  }


  // RHC, TDF (1747-RM001G p. 7-17): "an integer address (Nx:x) or Float address (Fx:x)", and TDF's
  // three "should be of the same data type". A time stamp is a word RHC wrote, never a constant.
  void check_clock_operands(const Instruction& in) {
    std::optional<FileType> first;
    for (const Operand& op : in.operands) {
      if (!op.is_address())
        return error(op.pos, mnemonic_of(in) + " takes N or F words (1747-RM001 p. 7-17), not the constant " + op.text());
      const FileType t = op.address.type;
      if (t != FileType::Integer && t != FileType::Float)
        return error(op.pos, mnemonic_of(in) + " takes N or F words (1747-RM001 p. 7-17), not " + op.text());
      if (first && *first != t)
        return error(op.pos, "TDF's start, stop and destination are all N words or all F words (1747-RM001 p. 7-17)");
      first = t;
    }
  }

  // SWP (1747-RM001G p. 4-28): "a bit, integer, ASCII, or string file"; in a string file at most
  // 41 words, inside one element's data words (.1-.41: word 0 is the length, not text).
  void check_swap(const Instruction& in) {
    const Operand& src = in.operands[0];
    const auto t = src.address.type;
    if (t != FileType::Bit && t != FileType::Integer && t != FileType::Ascii && t != FileType::String)
      return error(src.pos, "SWP swaps words of a B, N, A or ST file (1747-RM001 p. 4-28), not " +
                                std::string(file_letter(t)) + std::to_string(src.address.file));
    if (t != FileType::String) return;
    if (src.address.indirect_word()) return;  // known at run time only: the interpreter checks it
    const std::int64_t len = in.operands[1].integer;
    const int word = src.address.word;
    if (word < 1)
      return error(src.pos, "SWP on a string swaps its data words: name the first one, for example #ST" +
                                std::to_string(src.address.file) + ":" + std::to_string(src.address.element) +
                                ".1 (DATA[0]; word 0 is the length)");
    if (word + len - 1 > 41)
      error(in.operands[1].pos, "SWP of " + std::to_string(len) + " words from word " + std::to_string(word) +
                                    " leaves the string element (41 data words; 1747-RM001 p. 4-28: length 1-41, "
                                    "never across a string element boundary)");
  }

  // PID (1747-RM001G p. 9-3/9-4): the process variable is an element address (not a constant), and
  // neither it nor the control variable may lie inside the 23-word control block, which the
  // instruction rewrites every time it runs ("do not write to control block addresses with other
  // instructions").
  void check_pid(const Instruction& in) {
    const Operand& block = in.operands[0];
    const Operand& pv = in.operands[1];
    if (pv.is_number())
      error(pv.pos, "PID process variable: expected an element address that stores the process input (for example "
                    "I:1.0 or N10:28), found the constant '" + pv.text() + "' (1747-RM001G p. 9-4)");
    if (!block.is_address() || block.address.type != FileType::Integer || block.address.indirect_element() ||
        block.address.indirect_file() || block.address.indexed)
      return;
    const Address& b = block.address;
    for (std::size_t i = 1; i < 3; ++i) {
      const Operand& op = in.operands[i];
      if (!op.is_address()) continue;
      const Address& a = op.address;
      if (a.type != FileType::Integer || a.file != b.file || a.indirect_element() || a.indirect_file()) continue;
      if (a.element >= b.element && a.element < b.element + 23)
        error(op.pos, std::string(i == 1 ? "PID process variable " : "PID control variable ") + op.text() +
                          " lies inside the control block " + block.text() + " (N" + std::to_string(b.file) + ":" +
                          std::to_string(b.element) + " to N" + std::to_string(b.file) + ":" +
                          std::to_string(b.element + 22) + ", 23 words, 1747-RM001G p. 9-3), which the PID rewrites");
    }
  }

  // CPT: the expression parses, every operand is a word address or constant that could stand as
  // a Source operand, and bitwise operations (AND OR XOR NOT, TOD FRD) are not mixed with floating
  // point (the WordSource rule of the table, applied inside the expression).
  void check_cpt(const Instruction& in) {
    const Operand& e = in.operands[1];
    auto at = [&](std::size_t column) {
      return SourcePos{e.pos.line, e.pos.column + static_cast<std::uint32_t>(column)};
    };
    ExpressionError err;
    auto items = parse_expression(e.spelling, err);
    if (!items) return error(at(err.column), "CPT expression: " + err.message);
    bool is_float = in.operands[0].is_address() && in.operands[0].address.type == FileType::Float;
    std::string float_reason = is_float ? "the destination " + in.operands[0].text() + " is F" : "";
    const ExprItem* bitwise = nullptr;
    for (const auto& it : *items) {
      if (it.code != ExprCode::Push) {
        if (!bitwise && (expr_is_bitwise(it.code) || it.code == ExprCode::Tod || it.code == ExprCode::Frd))
          bitwise = &it;
        if (float_reason.empty() && expr_is_float_function(it.code))
          float_reason = std::string(to_string(it.code)) + " computes in floating point";
        continue;
      }
      NumberValue v;
      if (parse_number_text(it.text, v)) {
        if (v.is_float && float_reason.empty()) float_reason = "the constant " + it.text + " is floating point";
        if (v.is_float && !program_.processor.has_float_files())
          error(at(it.column), "floating-point constants need SLC 5/03 OS301 or later");
        continue;
      }
      std::string why;
      auto a = parse_address(it.text, &why);
      if (!a) {
        error(at(it.column), "CPT expression: '" + it.text + "' is not an address or a constant");
        continue;
      }
      if (a->has_bit()) {
        error(at(it.column), "CPT expression: " + it.text + " is a bit; the expression takes words and constants");
        continue;
      }
      if (is_structured(a->type) && a->word < 0) {
        error(at(it.column), "CPT expression: " + it.text + " is a whole element; name a word (.PRE, .ACC, .LEN or .POS)");
        continue;
      }
      if (uses_memdef_file(*a)) {
        error(at(it.column), "CPT expression: " + std::string(file_letter(a->type)) + std::to_string(a->file) +
                                 " holds the program's MEMDEF variables; name them instead (docs/automax.md)");
        continue;
      }
      check_address(*a, at(it.column), OperandKind::Source, MFileAccess::OtherM);
      if (a->type == FileType::Float && float_reason.empty()) float_reason = it.text + " is F";
    }
    if (bitwise && !float_reason.empty())
      error(at(bitwise->column), "CPT expression: " + std::string(to_string(bitwise->code)) +
                                     " works on integer words, but this expression computes in floating point (" +
                                     float_reason + ")");
  }

  // ---- Rung structure ----------------------------------------------------------------------------------

  struct SequenceInfo {
    bool has_output = false;
    bool ends_with_output = false;
    int instructions = 0;
  };

  // Checks one series of elements (a rung or a branch leg). The SLC solves a rung left to right:
  // conditions first, then outputs; an output may be followed only by more outputs or by an
  // output branch whose legs each end in an output.
  SequenceInfo check_sequence(std::vector<RungElement>& elems, bool top_level, int file_number, int rung_index,
                              int& instruction_counter) {
    SequenceInfo info;
    SourcePos first_output;
    for (std::size_t i = 0; i < elems.size(); ++i) {
      auto& e = elems[i];
      if (e.kind == RungElement::Kind::Instruction) {
        bool first = instruction_counter == 0;
        ++instruction_counter;
        ++info.instructions;
        check_instruction(e.instruction, first, file_number, rung_index);
        Role role = spec(e.instruction.opcode).role;
        bool is_output = role == Role::Output;
        if (is_output) {
          if (!info.has_output) first_output = e.pos();
          info.has_output = true;
          info.ends_with_output = true;
        } else {
          if (info.has_output && role == Role::Input)
            error(e.pos(), "input instruction " + mnemonic_of(e.instruction) +
                             " after an output instruction (line " + std::to_string(first_output.line) + ", column " +
                             std::to_string(first_output.column) +
                             "); the SLC places conditions before outputs — use a branch");
          info.ends_with_output = false;
        }
        if (e.instruction.opcode == Opcode::END && !(top_level && elems.size() == 1))
          error(e.pos(), "END stands alone on the last rung of a file");
      } else {
        bool any_output = false, all_output = true;
        std::vector<SequenceInfo> legs;
        legs.reserve(e.legs.size());
        for (auto& leg : e.legs) {
          legs.push_back(check_sequence(leg, false, file_number, rung_index, instruction_counter));
          any_output |= legs.back().has_output;
          all_output &= legs.back().ends_with_output;
        }
        if (any_output) {
          for (std::size_t l = 0; l < legs.size(); ++l)
            if (!legs[l].ends_with_output)
              error(e.pos(), "leg " + std::to_string(l + 1) +
                               " of this output branch does not end in an output instruction");
          if (!info.has_output) first_output = e.pos();
          info.has_output = true;
          info.ends_with_output = all_output;
        } else {
          if (info.has_output)
            error(e.pos(), "input branch after an output instruction; the SLC places conditions before outputs");
          info.ends_with_output = false;
        }
        info.instructions += 1;
      }
    }
    return info;
  }

  void check_file(ProgramFile& file) {
    if (file.number < 2 || file.number > 255) error(file.pos, "program files are numbered 2 (main) to 255");
    std::map<std::int64_t, SourcePos> labels;
    std::vector<std::pair<std::int64_t, SourcePos>> jumps;
    for (std::size_t r = 0; r < file.rungs.size(); ++r) {
      auto& rung = file.rungs[r];
      int counter = 0;
      unknown_in_rung_ = false;
      auto info = check_sequence(rung.elements, true, file.number, static_cast<int>(r), counter);
      if (!info.has_output) {
        // An unknown instruction is the error; that the rung then lacks an output follows from it.
        if (!unknown_in_rung_) error(rung.pos, "rung has no output instruction");
        continue;
      }
      if (!info.ends_with_output) error(rung.pos, "rung must end with an output instruction");
      for (const auto& e : rung.elements) collect_labels(e, labels, jumps);
      check_mcr_rung(rung);
      bool has_end = !rung.elements.empty() && rung.elements.front().kind == RungElement::Kind::Instruction &&
                     rung.elements.front().instruction.opcode == Opcode::END;
      if (has_end && r + 1 != file.rungs.size()) error(rung.pos, "END must be the last rung of the file");
    }
    // A rung lost to a syntax error may hold the label: no "not defined" that would follow from it.
    if (files_missing_rungs_.count(file.number)) return;
    for (const auto& [label, pos] : jumps)
      if (!labels.count(label))
        error(pos, "JMP to label " + std::to_string(label) + ", which is not defined in program file " +
                       std::to_string(file.number));
  }

  void collect_labels(const RungElement& e, std::map<std::int64_t, SourcePos>& labels,
                      std::vector<std::pair<std::int64_t, SourcePos>>& jumps) {
    if (e.kind == RungElement::Kind::Branch) {
      for (const auto& leg : e.legs)
        for (const auto& x : leg) collect_labels(x, labels, jumps);
      return;
    }
    const auto& in = e.instruction;
    if (in.operands.size() != 1 || in.operands[0].kind != Operand::Kind::Integer) return;
    if (in.opcode == Opcode::LBL) {
      auto [it, inserted] = labels.emplace(in.operands[0].integer, in.pos);
      if (!inserted)
        error(in.pos, "label " + std::to_string(in.operands[0].integer) + " is defined twice (first at line " +
                          std::to_string(it->second.line) + ")");
    } else if (in.opcode == Opcode::JMP) {
      jumps.emplace_back(in.operands[0].integer, in.operands[0].pos);
    }
  }

  static void count_instructions(const std::vector<RungElement>& elems, int& outputs, bool& has_mcr, SourcePos& mcr_pos) {
    for (const auto& e : elems) {
      if (e.kind == RungElement::Kind::Branch) {
        for (const auto& leg : e.legs) count_instructions(leg, outputs, has_mcr, mcr_pos);
        continue;
      }
      if (spec(e.instruction.opcode).role == Role::Output) ++outputs;
      if (e.instruction.opcode == Opcode::MCR) {
        has_mcr = true;
        mcr_pos = e.pos();
      }
    }
  }

  // An MCR is the only output of its rung (RM: "MCR ... must be the only output on the rung").
  void check_mcr_rung(const Rung& rung) {
    int outputs = 0;
    bool has_mcr = false;
    SourcePos mcr_pos;
    count_instructions(rung.elements, outputs, has_mcr, mcr_pos);
    if (has_mcr && outputs > 1) error(mcr_pos, "MCR must be the only output instruction on its rung");
  }

  void check_jsr_targets() {
    for (const auto& [target, pos] : jsr_targets_)
      if (!program_.find_file(target))
        error(pos, "JSR to program file " + std::to_string(target) + ", which is not defined (no LADDER " +
                       std::to_string(target) + ")");
    for (const auto& [target, pos] : isr_targets_)
      if (!program_.find_file(target))
        error(pos, "OPTION ISR names interrupt subroutine file " + std::to_string(target) +
                       ", which is not defined (no LADDER " + std::to_string(target) + ")");
    for (const auto& [target, pos] : sts_targets_)
      if (!program_.find_file(target))
        error(pos, "STS names STI file " + std::to_string(target) + ", which is not defined (no LADDER " +
                       std::to_string(target) + ")");
  }

  // ---- Data and forces -------------------------------------------------------------------------------

  void check_data_blocks() {
    std::set<std::pair<int, int>> seen;  // (type, file) pairs, to catch a file given twice
    for (const auto& d : program_.data) {
      if (!d.type) continue;
      const FileType t = *d.type;
      if (is_function_file(t)) {
        if (!seen.emplace(static_cast<int>(t), d.file).second) error(d.pos, "DATA for " + d.file_name + " is given twice");
        check_function_file_data(d);
        continue;
      }
      if (!seen.emplace(static_cast<int>(*d.type), d.file).second && !is_io(*d.type))
        error(d.pos, "DATA for " + std::string(file_letter(*d.type)) + std::to_string(d.file) + " is given twice");
      if (is_io(t)) {
        const SlotConfig* slot = slot_of(d.start_element);
        if (!slot) {
          error(d.pos, "DATA for slot " + std::to_string(d.start_element) + ", which has no module");
          continue;
        }
        int words = t == FileType::Input ? slot->scan_in : slot->scan_out;
        if (static_cast<int>(d.words.size()) > words)
          error(d.pos, std::to_string(d.words.size()) + " image words given for slot " +
                           std::to_string(d.start_element) + ", which has " + std::to_string(words));
      }
      if (t == FileType::Status && d.start_element + static_cast<int>(d.words.size()) > status_file_words(program_.processor))
        warning(d.pos, "status data beyond S:" + std::to_string(status_file_words(program_.processor) - 1) +
                           " of " + program_.processor.display_name + " is ignored");
      if (is_multiword_data(t) && d.words.size() % static_cast<std::size_t>(words_per_element(t)) != 0)
        error(d.pos, "each " + std::string(file_letter(t)) + " element takes " + std::to_string(words_per_element(t)) +
                         " values, its words 0-" + std::to_string(words_per_element(t) - 1) +
                         (t == FileType::Message ? " (1762-RM001C p. 21-4)" : " (1766-RM001A p. 435)"));
      if (is_structured(t) && d.words.size() % 3 != 0)
        error(d.pos, "each " + std::string(file_letter(t)) + " element takes three values (CTL, " +
                         (t == FileType::Control ? "LEN, POS" : "PRE, ACC") + ")");
      std::size_t elements = t == FileType::Float    ? d.floats.size()
                             : t == FileType::String ? d.strings.size()
                             : is_structured(t)      ? d.words.size() / 3
                             : is_multiword_data(t)  ? d.words.size() / static_cast<std::size_t>(words_per_element(t))
                                                     : d.words.size();
      if (!is_io(t) && t != FileType::Status && d.start_element + elements > 256)
        error(d.pos, "DATA runs past element 255 (" + std::to_string(elements) + " elements from " +
                         std::to_string(d.start_element) + ")");
      std::int64_t lo = t == FileType::Long ? INT32_MIN : -32768;
      std::int64_t hi = t == FileType::Long ? INT32_MAX : 65535;
      for (auto w : d.words)
        if (w < lo || w > hi) {
          error(d.pos, "value " + std::to_string(w) + " does not fit a " +
                           (t == FileType::Long ? "32-bit" : "16-bit") + " word");
          break;
        }
    }
  }

  // A DATA block that gives a function file its values: the STI's is its one element, the four
  // words in the order RSLogix exports them (PFN ER bits SPM; sti:: in parser/address.h).
  void check_function_file_data(const DataBlock& d) {
    if (!program_.processor.is_micrologix_1100_class())
      return error(d.pos, "function file data (" + d.file_name + ") belongs to a MicroLogix 1100, 1200, 1400 or "
                          "1500; this program's processor is " + program_.processor.display_name);
    if (is_pulse_train_file(d.file)) return check_pulse_train_data(d);
    if (d.file == static_cast<int>(FunctionFile::HSC)) return check_hsc_data(d);
    if (d.file == static_cast<int>(FunctionFile::EII)) return check_eii_data(d);
    if (d.start_element != 0 || d.words.size() != static_cast<std::size_t>(sti::kWords))
      return error(d.pos, "DATA " + d.file_name + ": the STI function file has one element of four words, "
                          "PFN ER bits SPM, as RSLogix exports it (for example 3 0 0X0032 1000)");
    for (auto w : d.words)
      if (w < -32768 || w > 65535) return error(d.pos, "value " + std::to_string(w) + " does not fit a 16-bit word");
  }

  // DATA PTO0:0 / PTOX0:0: nine values per element from element 0 (OUT, bits, ER, OF, OFS, JF, TOP,
  // OPP, ADP, the order RSLogix exports a PTOX element in), each within its word's width.
  void check_pulse_train_data(const DataBlock& d) {
    // Another MicroLogix's block (a 1400 export's PTOX0:0 retargeted to an 1100) configures nothing
    // here: kept, unused, with a warning, as the function files softslc does not model.
    const bool ml1400 = program_.processor.micrologix == MicroLogixModel::ML1400;
    if (ml1400 != (d.file == static_cast<int>(FunctionFile::PTOX)))
      return warning(d.pos, "DATA " + d.file_name + " configures the pulse train output of " +
                                (ml1400 ? "a MicroLogix 1100, 1200 or 1500 (PTO)" : "a MicroLogix 1400 (PTOX)") + "; the " +
                                program_.processor.display_name + "'s is " + (ml1400 ? "PTOX" : "PTO") + ": not used");
    const int elements = function_file_elements(d.file);
    const std::string name(function_file_name(d.file));
    if (d.start_element != 0 || d.words.empty() || d.words.size() % pto::kValuesPerElement != 0 ||
        d.words.size() / pto::kValuesPerElement > static_cast<std::size_t>(elements))
      return error(d.pos, "DATA " + d.file_name + ": each " + name + " element takes nine values, OUT bits ER OF OFS JF TOP OPP "
                          "ADP, as RSLogix exports them (for example -1 0X0000 0 0 0 0 0 0 0), for elements 0-" +
                          std::to_string(elements - 1));
    const bool wide = d.file == static_cast<int>(FunctionFile::PTOX);
    for (std::size_t i = 0; i < d.words.size(); ++i) {
      const std::size_t k = i % pto::kValuesPerElement;
      const bool is_long = k >= 6 || (wide && k >= 3);
      const std::int64_t lo = is_long ? INT32_MIN : -32768, hi = is_long ? INT32_MAX : 65535;
      if (d.words[i] < lo || d.words[i] > hi)
        return error(d.pos, "value " + std::to_string(d.words[i]) + " does not fit " + name + " " +
                                (is_long ? "long word" : "word") + " (value " + std::to_string(k + 1) + " of element " +
                                std::to_string(i / pto::kValuesPerElement) + ")");
    }
  }

  // How many of a function file's `elements` in DATA block `d` the processor's `count` takes. A program
  // moved to a processor with fewer (the MicroLogix 1400's six counters or eight EIIs to an 1100): the
  // extra elements left as RSLogix created them (`is_default(e)`) are dropped with a warning; a
  // configured one is an error, and none is used then.
  template <typename IsDefault>
  std::size_t elements_to_use(const DataBlock& d, std::size_t elements, int count, const std::string& file,
                              const std::string& what, IsDefault is_default) {
    if (elements <= static_cast<std::size_t>(count)) return elements;
    for (std::size_t e = static_cast<std::size_t>(count); e < elements; ++e)
      if (!is_default(e)) {
        error(d.pos, "DATA " + d.file_name + " configures " + file + ":" + std::to_string(e) + "; the " +
                         program_.processor.display_name + " has " + std::to_string(count) + " " + what);
        return 0;
      }
    warning(d.pos, "DATA " + d.file_name + " gives " + std::to_string(elements) + " " + file + " elements; the " +
                       program_.processor.display_name + " has " + std::to_string(count) +
                       ": the others hold RSLogix's defaults and are dropped");
    return static_cast<std::size_t>(count);
  }

  // DATA HSC0:0: each element's 13 values as RSLogix exports them (hsc:: in parser/address.h), one
  // element per high-speed counter of the processor. The HSC sub-system refuses a configuration whose
  // OVF is below HIP (1762-RM001C p. 5-23 says "greater than", but RSLogix's own default has both at
  // 2147483647, so equal is accepted) or whose UNF is above LOP (1766-RM001A p. 127), and
  // softslc runs mode 0 only (docs/semantics.md "The HSC function file"): both are found here.
  void check_hsc_data(const DataBlock& d) {
    const int count = program_.processor.hsc_count();
    if (d.start_element != 0 || d.words.empty() || d.words.size() % hsc::kExportValues != 0)
      return error(d.pos, "DATA " + d.file_name + ": each HSC element is 13 values as RSLogix exports it: PFN ER bits "
                          "bits MOD, then ACC HIP LOP OVF UNF, then OMB HPO LPO");
    static constexpr std::array<std::int64_t, hsc::kExportValues> kDefault{
        0, 0, hsc::kDefaultBits, hsc::kDefaultStatus, 0, 0, INT32_MAX, INT32_MIN, INT32_MAX, INT32_MIN, 0, 0, 0};
    const auto is_default = [&](std::size_t e) {
      for (std::size_t k = 0; k < hsc::kExportValues; ++k)
        if (d.words[e * hsc::kExportValues + k] != kDefault[k]) return false;
      return true;
    };
    const std::size_t elements =
        elements_to_use(d, d.words.size() / hsc::kExportValues, count, "HSC", "high-speed counter(s)", is_default);
    for (std::size_t e = 0; e < elements; ++e) {
      const auto v = [&](std::size_t k) { return d.words[e * hsc::kExportValues + k]; };
      const std::string at = "HSC:" + std::to_string(e);
      for (std::size_t k = 0; k < hsc::kExportValues; ++k)
        if (!hsc::export_value_is_long(k) && (v(k) < -32768 || v(k) > 65535))
          return error(d.pos, "value " + std::to_string(v(k)) + " does not fit a 16-bit word");
      const int pfn = static_cast<int>(static_cast<std::uint16_t>(v(hsc::kProgramFile)));
      if (pfn != 0 && (pfn < 3 || pfn > 255 || !program_.find_file(pfn)))
        error(d.pos, at + ".PFN " + std::to_string(pfn) + " is not a subroutine file of this program (3-255, no LADDER " +
                         std::to_string(pfn) + ")");
      if (const auto mode = v(hsc::kMode); mode != 0)
        error(d.pos, at + ".MOD " + std::to_string(mode) + ": softslc simulates HSC mode 0 (up counter) only; the "
                          "description of mode " + std::to_string(mode) + " (1762-RM001C p. 5-16) was not found, so it "
                          "is not guessed (docs/semantics.md \"The HSC function file\")");
      const auto hip = v(6), lop = v(7), ovf = v(8), unf = v(9);
      if (ovf < hip)
        error(d.pos, at + ": OVF " + std::to_string(ovf) + " must not be less than HIP " + std::to_string(hip) +
                         " or the HSC sub-system gives an error (1762-RM001C p. 5-23; equal is RSLogix's own default)");
      if (unf > lop)
        error(d.pos, at + ": UNF " + std::to_string(unf) + " must be less than or equal to LOP " + std::to_string(lop) +
                         " or the HSC sub-system gives an error (1766-RM001A p. 127)");
    }
  }

  // DATA EII0:0: four words an element (PFN ER bits IS, as RSLogix exports them; eii:: in
  // parser/address.h), from element 0, one element per event input of the processor. A PFN that is
  // set must be a ladder file 3-255 (error code 1, as the STI's, 1763-RM001C p. 270), and so must it
  // be when the EII can fire (EIE or AS set); IS must name an embedded input bit 0-15 [U]
  // (docs/semantics.md "The EII function file"). Found here rather than as the controller's error on
  // entering Run, so that `check` exit 0 means the program runs.
  void check_eii_data(const DataBlock& d) {
    const int count = program_.processor.eii_count();
    if (d.start_element != 0 || d.words.empty() || d.words.size() % eii::kWords != 0)
      return error(d.pos, "DATA " + d.file_name + ": each EII element is four values, PFN ER bits IS, as RSLogix exports it "
                          "(for example 3 0 0X4032 0)");
    // RSLogix's default element n: 0 0 0X4002 n (59-BSGS.SLC).
    const auto is_default = [&](std::size_t e) {
      const auto v = [&](int k) { return d.words[e * eii::kWords + static_cast<std::size_t>(k)]; };
      return v(eii::kProgramFile) == 0 && v(eii::kErrorCode) == 0 && v(eii::kBits) == eii::kDefaultBits &&
             v(eii::kInputSelect) == static_cast<std::int64_t>(e);
    };
    const std::size_t elements =
        elements_to_use(d, d.words.size() / eii::kWords, count, "EII", "event input interrupts", is_default);
    for (auto w : d.words)
      if (w < -32768 || w > 65535) return error(d.pos, "value " + std::to_string(w) + " does not fit a 16-bit word");
    for (std::size_t e = 0; e < elements; ++e) {
      const auto v = [&](int k) { return static_cast<std::uint16_t>(d.words[e * eii::kWords + static_cast<std::size_t>(k)]); };
      const std::string at = "EII:" + std::to_string(e);
      const int pfn = v(eii::kProgramFile);
      const bool can_fire = (v(eii::kBits) >> eii::kEventEnableBit & 1u) || (v(eii::kBits) >> eii::kAutoStartBit & 1u);
      if (pfn != 0 && (pfn < 3 || pfn > 255 || !program_.find_file(pfn)))
        error(d.pos, at + ".PFN " + std::to_string(pfn) + " is not a subroutine file of this program (3-255, no LADDER " +
                         std::to_string(pfn) + "): error code 1, Invalid Program File Number (1763-RM001C p. 270, as the STI's)");
      else if (pfn == 0 && can_fire)
        error(d.pos, at + "/EIE or /AS is set but " + at + ".PFN is 0: give the EII's program file (3-255)");
      if (const int input = static_cast<std::int16_t>(v(eii::kInputSelect)); input < 0 || input > eii::kMaxInput)
        error(d.pos, at + ".IS " + std::to_string(input) + " names no embedded input: 0-" + std::to_string(eii::kMaxInput) +
                         ", a bit of I:0.0 (docs/semantics.md \"The EII function file\")");
    }
  }

  // The STI's program file (STI:0.PFN) must be a ladder file of the program when it is set, and when
  // the STI can start (auto start, or an STS): 1763-RM001C p. 270, STI error code 1 "Invalid Program
  // File Number: less than 3, greater than 255, or does not exist". softslc finds it here, at the
  // DATA block that sets it, rather than as the controller's fault on entering Run (docs/semantics.md
  // "MicroLogix").
  void check_sti_function_file() {
    const DataBlock* block = nullptr;
    for (const auto& d : program_.data)
      if (d.type && is_function_file(*d.type) && d.file == static_cast<int>(FunctionFile::STI)) block = &d;
    const bool sized = block && block->words.size() == static_cast<std::size_t>(sti::kWords);
    const int pfn = sized ? static_cast<int>(static_cast<std::uint16_t>(block->words[sti::kProgramFile])) : 0;
    const bool auto_start = sized && ((static_cast<std::uint16_t>(block->words[sti::kBits]) >> sti::kAutoStartBit) & 1u);
    if (pfn != 0 && (pfn < 3 || pfn > 255 || !program_.find_file(pfn))) {
      error(block->pos, "STI:0.PFN " + std::to_string(pfn) + " is not a subroutine file of this program (3-255, no LADDER " +
                            std::to_string(pfn) + "): the STI's error code 1, Invalid Program File Number "
                            "(1763-RM001C p. 270)");
      return;
    }
    if (pfn != 0) return;
    if (auto_start)
      error(block->pos, "STI:0/AS (auto start) is set but STI:0.PFN is 0: give the STI's program file (3-255)");
    for (const auto& pos : ml_sts_uses_)
      error(pos, "STS starts the STI function file, whose program file STI:0.PFN is 0: give it in a DATA STI:0 block "
                 "(PFN ER bits SPM, for example 3 0 0X0002 0)");
  }

  void check_forces() {
    for (const auto& f : program_.forces) {
      const SlotConfig* slot = slot_of(f.slot);
      if (!slot) {
        error(f.pos, "FORCE for slot " + std::to_string(f.slot) + ", which has no module");
        continue;
      }
      int words = f.type == FileType::Input ? slot->scan_in : slot->scan_out;
      if (static_cast<int>(f.words.size()) > words)
        error(f.pos, std::to_string(f.words.size()) + " force words given for slot " + std::to_string(f.slot) +
                         ", which has " + std::to_string(words));
    }
  }

  // "The bit address you use must be unique. Do not use it elsewhere in the program" (RSLogix help).
  void check_osr_storage() {
    std::map<std::string, SourcePos> first_use;  // keyed by canonical spelling, ordered for determinism
    for (const auto& [address, pos] : osr_bits_) {
      auto [it, inserted] = first_use.emplace(to_string(address), pos);
      if (!inserted)
        warning(pos, "OSR storage bit " + it->first + " is also used by the OSR at line " +
                         std::to_string(it->second.line) + "; each OSR needs its own bit");
    }
  }
};

}  // namespace

int status_file_words(const ProcessorModel& p) {
  // Status file lengths: 5/01 and 5/02 S:0-S:32 (PT1); 5/03-5/05 S:0-S:163 (RSLogix 500 shows up
  // to S:163 on 5/05; [U], chosen generously so no valid program is rejected); MicroLogix 1400
  // S:0-S:65 (the fixture's DATA S:0 block); fixed controllers S:0-S:15.
  switch (p.family) {
    case ProcessorFamily::Fixed: return 16;
    case ProcessorFamily::Slc501:
    case ProcessorFamily::Slc502: return 33;
    case ProcessorFamily::MicroLogix: return 66;
    default: return 164;
  }
}

int m0_words(const SlotConfig& slot) {
  if (slot.m0_size) return *slot.m0_size;
  auto e = find_module_catalog(slot.catalog);
  return e ? e->default_m0 : 0;
}

int m1_words(const SlotConfig& slot) {
  if (slot.m1_size) return *slot.m1_size;
  auto e = find_module_catalog(slot.catalog);
  return e ? e->default_m1 : 0;
}

void check_program(Program& program, DiagnosticList& diags, const std::set<int>& files_missing_rungs) {
  Checker(program, diags, files_missing_rungs).run();
}

Program retarget_program(const Program& program, const ProcessorModel& processor, DiagnosticList& diags) {
  Program p = program;
  p.processor = processor;
  std::erase_if(p.slots, [](const SlotConfig& s) { return s.implicit; });
  check_program(p, diags);
  return p;
}

std::span<const std::string_view> real_mnemonics_without_rows() {
  // Instructions of the SLC 500 and MicroLogix instruction sets (1747-RM001G, 1762/1763/1766-RM001)
  // that have no row in the instruction table yet. tests/parser keeps this list in agreement with
  // the table: a name that gets a row must leave it (the table wins anyway: a name found there never
  // reaches unknown_instruction_message).
  static constexpr std::string_view kReal[] = {
      // MicroLogix only: high-speed counter and outputs, real-time clock adjust, data logging, LCD.
      "GCD", "HSC", "HSD", "HSE", "LCD", "PWM", "RCP"};
  return kReal;
}

std::string unknown_instruction_message(std::string_view name) {
  const auto real = real_mnemonics_without_rows();
  if (rss::is_known_rslogix_mnemonic(name) || std::find(real.begin(), real.end(), name) != real.end())
    return "instruction " + std::string(name) + " is not supported by softslc yet";
  // Decided in docs/semantics.md "BTD": no SLC 5/0x or MicroLogix has it.
  if (name == "BTD")
    return "BTD is not an SLC 500 instruction: bit field distribute belongs to the PLC-5 and Logix controllers; "
           "1747-RM001G and the MicroLogix instruction set references have none";
  return "unknown instruction '" + std::string(name) + "'";
}

std::string check_tool_address(const Program& program, const Address& a) {
  DiagnosticList diags;
  // The checker takes the program mutably because run() resolves symbols in place; checking one
  // address reads it only.
  Checker(const_cast<Program&>(program), diags).check_tool_address(a);
  for (const auto& d : diags.items())
    if (d.severity == Severity::Error) return to_string(a) + ": " + d.message;
  return {};
}

}  // namespace softslc
