#include "modules/sn/block_transfer.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <span>
#include <functional>
#include <map>

#include "instructions/instruction_table.h"

namespace softslc::rio {

void execute_block_transfer(ModuleInstructionContext& ctx) {
  const bool btr = ctx.opcode() == Opcode::BTR;
  const auto ops = ctx.operands();
  if (ops.size() < 3 || ops[0].kind != ModuleOperand::Kind::Table || ops[1].kind != ModuleOperand::Kind::MFile ||
      ops[2].kind != ModuleOperand::Kind::Table) {
    ctx.fault(0x001F, std::string(btr ? "BTR" : "BTW") + ": malformed operands");
    return;
  }
  const int slot = ops[1].slot;
  const int base = static_cast<int>(ops[1].word);
  std::uint16_t cb[3];
  if (!ctx.read_block(0, 0, cb)) return;

  const bool rung = ctx.rung_in();
  const bool was_enabled = (cb[0] & kEN) && !ctx.first_pass();
  // The instruction type decides RW (Table 5.2: "This bit is controlled by the instruction type").
  cb[0] = static_cast<std::uint16_t>(btr ? (cb[0] | kRW) : (cb[0] & ~kRW));
  if (rung && !was_enabled) {
    // "Before executing a block transfer, the BTR and BTW instructions clear all status bits and
    // initialize word 2 to 0."
    cb[0] = static_cast<std::uint16_t>(cb[0] & ~kStatusBits);
    cb[2] = 0;
    if (!btr) {
      const auto requested = static_cast<std::int16_t>(cb[1]);
      const int n = requested > 0 && requested <= kMaxWords ? requested : kMaxWords;
      const int available = static_cast<int>(std::min<std::uint32_t>(ops[2].limit, static_cast<std::uint32_t>(n)));
      ctx.charge(MFileAccess::CopToM, n);
      for (int k = 0; k < n; ++k) {
        std::uint16_t v = 0;
        if (k < available && !ctx.read(2, static_cast<std::uint32_t>(k), v)) return;
        if (!ctx.write_m(slot, MFile::M0, base + kDataOffset + k, v)) return;
      }
    }
  }
  cb[0] = static_cast<std::uint16_t>(rung ? (cb[0] | kEN) : (cb[0] & ~kEN));

  // Tell the scanner: the control word (EN, TO, RW, address) and the requested count.
  ctx.charge(MFileAccess::OtherM, 1);
  if (!ctx.write_m(slot, MFile::M0, base + kRequestedCount, cb[1])) return;
  ctx.charge(MFileAccess::OtherM, 1);
  if (!ctx.write_m(slot, MFile::M0, base + kControlWord,
                   static_cast<std::uint16_t>(cb[0] & (kEN | kTO | kRW | kAddressBits))))
    return;

  // Read its answer.
  std::uint16_t st[4];
  ctx.charge(MFileAccess::CopFromM, 4);
  if (ctx.read_m_block(slot, MFile::M1, base, st) != std::size(st)) return;
  const bool had_done = (cb[0] & kDN) != 0;
  cb[0] = static_cast<std::uint16_t>((cb[0] & ~kStatusBits) | (st[0] & kStatusBits));
  if (cb[0] & kDN) cb[2] = st[kTransmittedCount];
  else if (cb[0] & kER) cb[2] = st[kErrorCode];
  else cb[2] = 0;

  if (btr && (cb[0] & kDN) && !had_done) {
    // Step 2: "the DN bit is set ... the number of valid data words received ... is stored in
    // the BTR data file."
    const int n = std::clamp<int>(static_cast<std::int16_t>(st[kTransmittedCount]), 0, kMaxWords);
    ctx.charge(MFileAccess::CopFromM, n);
    // The words that fit the data file in one M1 read, then copied: the same words written as word
    // by word, also when a read is refused (the words before it are written, then the fault). A
    // word past the data file's end is read and then faults on its write, as word by word.
    const auto fits = std::min<std::uint32_t>(ops[2].limit, static_cast<std::uint32_t>(n));
    std::array<std::uint16_t, kMaxWords> data{};
    const std::size_t got = ctx.read_m_block(slot, MFile::M1, base + kDataOffset, std::span(data.data(), fits));
    if (!ctx.write_block(2, 0, std::span<const std::uint16_t>(data.data(), got)) || got < fits) return;
    for (int k = static_cast<int>(fits); k < n; ++k) {
      std::uint16_t v = 0;
      if (!ctx.read_m(slot, MFile::M1, base + kDataOffset + k, v)) return;
      if (!ctx.write(2, static_cast<std::uint32_t>(k), v)) return;
    }
  }
  for (std::uint32_t k = 0; k < 3; ++k)
    if (k != 1 && !ctx.write(0, k, cb[k])) return;
}

void check_buffer_sharing(const Program& program, int slot, DiagnosticList& diags) {
  struct FirstUse {
    const Instruction* instruction;
    int file, rung;
  };
  std::map<int, FirstUse> users;  // buffer number -> its first BTR/BTW
  std::function<void(const std::vector<RungElement>&, int, int)> walk = [&](const std::vector<RungElement>& elements,
                                                                              int file, int rung) {
    for (const auto& e : elements) {
      if (e.kind == RungElement::Kind::Branch) {
        for (const auto& leg : e.legs) walk(leg, file, rung);
        continue;
      }
      const Instruction& in = e.instruction;
      if ((in.opcode != Opcode::BTR && in.opcode != Opcode::BTW) || in.operands.size() < 2) continue;
      const Operand& control = in.operands[0];
      const Operand& buffer = in.operands[1];
      if (!buffer.is_address() || buffer.address.element != slot) continue;
      const int x = buffer_at(buffer.address.word);
      if (x == 0) continue;  // not a buffer address: the checker has said so
      auto [it, first] = users.try_emplace(x, FirstUse{&in, file, rung});
      if (first) continue;
      const Instruction& other = *it->second.instruction;
      if (control.is_address() && other.operands[0].is_address() && control.address == other.operands[0].address)
        continue;
      diags.error(buffer.pos.line, buffer.pos.column,
                  "block-transfer buffer " + std::to_string(x) + " of the 1747-SN in slot " + std::to_string(slot) +
                      " (M0:" + std::to_string(slot) + "." + std::to_string(x * kBufferStride) + " and M1:" +
                      std::to_string(slot) + "." + std::to_string(x * kBufferStride) + ") is already used by " +
                      std::string(spec(other.opcode).mnemonic) + " " + other.operands[0].text() + " in file " +
                      std::to_string(it->second.file) + " rung " + std::to_string(it->second.rung) + " (line " +
                      std::to_string(other.pos.line) + "): the scanner has 32 buffers, one per block transfer; " +
                      "\"the next BT instruction must use another M-file buffer\" (1747-SN p. 5-6)");
    }
  };
  for (const auto& f : program.files)
    for (std::size_t r = 0; r < f.rungs.size(); ++r) walk(f.rungs[r].elements, f.number, static_cast<int>(r));
}

}  // namespace softslc::rio
