// Shared fixtures for the DeviceNet tests: the manual's example network (chapters 2-4: a 1747-SDN at
// node 0, a RediSTATION at node 7 polled, a Series 9000 photoeye at node 9 strobed, 500 kbit/s;
// p.43-44 and p.52) with the scanlist RSNetWorx AutoMap produced (p.58-61), and helpers that step
// virtual time.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "modules/devicenet/device_model.h"
#include "modules/devicenet/network.h"
#include "modules/devicenet/scanlist.h"
#include "modules/devicenet/scanner.h"
#include "modules/devicenet/tables.h"
#include "modules/devicenet/transaction.h"

namespace softslc::devicenet::test {

inline constexpr int kScannerNode = 0;     // p.52: "the 1747-SDN module should have a node address of 0"
inline constexpr int kRediStationNode = 7; // p.43: DIP switches 000111 = node 7
inline constexpr int kPhotoeyeNode = 9;    // p.44: "Node address: 9"
inline constexpr int kDriveNode = 20;      // not in the manual: our drive for explicit messaging

inline MapSegment segment(IoType t, int byte, int bit, int bits, TableRef::Area area, int word, int tbit) {
  return MapSegment{t, byte, bit, TableRef{area, word, tbit}, bits};
}

// The chapter 4 AutoMap result: RediSTATION input -> M1:0 bits 0-7, photoeye -> M1:0 bits 8-15,
// RediSTATION output <- M0:0 bits 0-7 (p.58-61).
inline ScannerConfig example_config(bool with_drive = false) {
  ScannerConfig c;
  c.node_address = kScannerNode;
  c.baud = Baud::k500;
  ScanlistEntry redi;
  redi.node = kRediStationNode;
  redi.conn(IoType::Poll) = ConnectionConfig{true, 1, 1, default_epr(IoType::Poll), false};
  redi.inputs.push_back(segment(IoType::Poll, 0, 0, 8, TableRef::Area::MFile, 0, 0));
  redi.outputs.push_back(segment(IoType::Poll, 0, 0, 8, TableRef::Area::MFile, 0, 0));
  ScanlistEntry eye;
  eye.node = kPhotoeyeNode;
  eye.conn(IoType::Strobe) = ConnectionConfig{true, 1, 0, default_epr(IoType::Strobe), false};
  eye.inputs.push_back(segment(IoType::Strobe, 0, 0, 8, TableRef::Area::MFile, 0, 8));
  c.scanlist = {redi, eye};
  if (with_drive) {
    ScanlistEntry drive;
    drive.node = kDriveNode;
    drive.conn(IoType::Poll) = ConnectionConfig{true, 4, 4, default_epr(IoType::Poll), false};
    drive.inputs.push_back(segment(IoType::Poll, 0, 0, 32, TableRef::Area::MFile, 2, 0));
    drive.outputs.push_back(segment(IoType::Poll, 0, 0, 32, TableRef::Area::MFile, 2, 0));
    c.scanlist.push_back(drive);
  }
  return c;
}

struct ExampleNetwork {
  explicit ExampleNetwork(bool with_drive = false, std::optional<ScannerConfig> config = std::nullopt)
      : net(Baud::k500) {
    redi = &net.attach(kRediStationNode, builtin_device_model("redistation"));
    eye = &net.attach(kPhotoeyeNode, builtin_device_model("series-9000-photoeye"));
    if (with_drive) drive = &net.attach(kDriveNode, builtin_device_model("ac-drive"));
    sdn = std::make_unique<Scanner>(net, config ? *config : example_config(with_drive));
  }

  // Sets the command register (output image word 0) and leaves the discrete outputs at 0.
  void command(std::uint16_t word) {
    const std::uint16_t image[1] = {word};
    sdn->write_output_image(image);
  }
  void run() { command(bit(CommandBit::Run)); }
  void idle() { command(0); }
  void advance_ms(std::int64_t ms) { net.advance_to(net.now() + milliseconds(ms)); }
  // Port start (2 s duplicate MAC check) plus the first connections and a few scans.
  void start() { advance_ms(2200); }

  std::uint16_t m1(int word) const {
    std::uint16_t v = 0;
    sdn->read_m(MFile::M1, word, v);
    return v;
  }
  void m0(int word, std::uint16_t v) { sdn->write_m(MFile::M0, word, v); }

  Network net;
  SimDevice* redi = nullptr;
  SimDevice* eye = nullptr;
  SimDevice* drive = nullptr;
  std::unique_ptr<Scanner> sdn;
};

inline bool table_bit(const ExampleNetwork& x, int base, int node) {
  return ((x.m1(base + node / 16) >> (node % 16)) & 1) != 0;
}

}  // namespace softslc::devicenet::test
