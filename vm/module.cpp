#include "vm/module.h"

#include "vm/faults.h"

namespace softslc {

std::string_view to_string(Mode m) {
  switch (m) {
    case Mode::Program: return "program";
    case Mode::Run: return "run";
    case Mode::Test: return "test";
    case Mode::Faulted: return "faulted";
    case Mode::Suspended: return "suspended";
  }
  return "?";
}

std::string_view to_string(MAccess a) {
  switch (a) {
    case MAccess::Ok: return "ok";
    case MAccess::NoSuchWord: return "no such word";
    case MAccess::Forbidden: return "forbidden";
  }
  return "?";
}

MAccess Module::read_m_block(MFile f, int word, std::span<std::uint16_t> out, std::size_t& done) {
  for (done = 0; done < out.size(); ++done) {
    const MAccess a = read_m(f, word + static_cast<int>(done), out[done]);
    if (a != MAccess::Ok) return a;
  }
  return MAccess::Ok;
}

void Module::execute(ModuleInstructionContext& ctx) {
  ctx.fault(fault::kUnsupportedInstruction, std::string(spec(ctx.opcode()).mnemonic) + ": the module in slot " +
                                               std::to_string(slot_) + " (" + catalog_ + ") has no such instruction");
}

}  // namespace softslc
