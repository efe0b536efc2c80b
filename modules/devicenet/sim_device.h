// SimDevice: one running simulated DeviceNet slave built from a DeviceModel.
//
// The device is passive, as a slave is: it answers what the master asks and never decides the
// time of anything itself. The scanner (or a test) calls allocate() to open the predefined
// master/slave connections, produce()/consume() for each I/O message, handle() for each explicit
// request, and master_lost() when the device's connection watchdog would expire. Field-side
// changes (a button pressed, a beam broken) go through set_input(); the network forwards them to
// the master as change-of-state notifications through the callback set_input_listener() installs.
//
// Its explicit-message server implements, with the CIP general status codes of chapter 8 (p.99):
//   Identity   (class 1)    instance 1: 1 vendor, 2 device type, 3 product code, 4 revision,
//                           5 status, 6 serial, 7 product name; Get_Attribute_Single,
//                           Get_Attributes_All, Reset (type 0 or 1; other types 0x20)
//   DeviceNet  (class 3)    instance 1: 1 MAC ID, 2 baud rate (read-only here: switches)
//   Assembly   (class 4)    the described instances; attribute 3 is the input or output image;
//                           setting an output assembly needs the exact size (0x13/0x15) and is
//                           refused with 0x10 while a Run I/O connection owns the outputs
//   Connection (class 5)    instances 2 poll, 3 strobe, 4 COS/cyclic (when supported):
//                           1 state, 7 produced size, 8 consumed size, 9 expected packet rate (set)
//   Parameter  (class 0x0F) one instance per parameter: 1 value (set: exact size, range → 0x09,
//                           read-only → 0x0E), 2 link path size, 3 link path, 4 descriptor
//                           (bit 4 = read only), 5 data type, 6 data size, 7 name, 8 units,
//                           9 help, 10 min, 11 max, 12 default
//   vendor objects          the described attributes, Get/Set_Attribute_Single and
//                           Get_Attributes_All (every attribute in id order)
// Every class answers instance 0 attribute 1 (revision) and 2 (max instance). Unknown classes and
// instances give 0x16, unknown attributes 0x14, services a class lacks 0x08, missing or extra
// request bytes 0x13/0x15.
//
// Failure injections (offline, wrong produced size, idle, identity override, explicit silence,
// ownership by another master) change only what the device does on the wire, never the model.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "modules/devicenet/bus_timing.h"
#include "modules/devicenet/cip.h"
#include "modules/devicenet/device_model.h"

namespace softslc::devicenet {

// What the device's outputs are doing (what the field sees).
enum class OutputState : std::uint8_t {
  NotConnected,  // no master has allocated the device since power-up or since it was lost
  Run,           // outputs follow the master's Run data
  Idle,          // the master sent zero-length (idle) data: the model's idle action applies
  Fault,         // the master went silent: the model's fault action applies
};
std::string_view to_string(OutputState s);

class SimDevice {
 public:
  explicit SimDevice(DeviceModel model);

  const DeviceModel& model() const { return model_; }

  // ---- network side -------------------------------------------------------------------------
  void set_address(int mac, Baud baud) { mac_ = mac; baud_ = baud; }
  int mac() const { return mac_; }
  bool online() const { return online_; }
  // The identity the device reports (the model's, unless an override is injected).
  const Identity& identity() const { return identity_override_ ? *identity_override_ : model_.identity; }

  enum class AllocateResult : std::uint8_t { Ok, NoResponse, Refused };
  // Opens the predefined master/slave connections of the given types (Allocate_Master/Slave).
  AllocateResult allocate(std::span<const IoType> types);
  bool allocated() const { return allocated_; }
  bool supports(IoType t) const { return model_.support(t).supported; }
  // Sizes the Connection object reports (attributes 7 and 8): the model's, or the injected size.
  int produced_size(IoType t) const;
  int consumed_size(IoType t) const;
  // The device's answer to an I/O message: nullopt = silent (offline or not allocated); empty =
  // the zero-length idle message; otherwise produced_size(t) bytes of the input image.
  std::optional<Bytes> produce(IoType t) const;
  // produce(t)'s length without building it (the scanner's cycle needs only the frame's length).
  std::optional<int> produced_length(IoType t) const {
    if (!online_ || !allocated_ || !supports(t)) return std::nullopt;
    return producing_idle_ ? 0 : produced_size(t);
  }
  // Receives output data: empty = idle (idle action) for a connection that consumes data, nothing
  // for one that does not (an input-only device is polled with zero-length commands); otherwise
  // Run data. A strobe delivers the device's single strobe bit as output byte 0, bit 0.
  void consume(IoType t, std::span<const std::uint8_t> data);
  // The device's connection watchdog expired: fault action, connections released.
  void master_lost();
  // Whether the device answers explicit requests at all (online and not made silent).
  bool answers_explicit() const { return online_ && !explicit_silent_; }
  // Serves one explicit request.
  CipReply handle(const CipRequest& request);

  // ---- field side ---------------------------------------------------------------------------
  // Sets a named input point; false when the model has no such point.
  bool set_input(std::string_view point, bool value);
  void set_input_byte(int byte, std::uint8_t value);  // byte outside the image: ignored
  const Bytes& inputs() const { return inputs_; }
  const Bytes& outputs() const { return outputs_; }
  std::optional<bool> input(std::string_view point) const;
  std::optional<bool> output(std::string_view point) const;
  OutputState output_state() const { return output_state_; }
  // How many I/O messages of each type the device has consumed (for tests and tools).
  std::uint64_t messages_consumed(IoType t) const { return consumed_[static_cast<std::size_t>(t)]; }
  // Called after every input change (the network uses it for change-of-state production).
  void set_input_listener(std::function<void()> f) { on_input_change_ = std::move(f); }

  // ---- failure injection --------------------------------------------------------------------
  // Offline: the device neither answers nor consumes; going offline drops its connections and
  // de-energises its outputs, as a power loss does.
  void set_online(bool online);
  // Wrong data size: every I/O connection reports and produces `bytes` bytes (nullopt = model).
  void set_produced_size_override(std::optional<int> bytes) { size_override_ = bytes; }
  // Idle: the device produces zero-length data.
  void set_producing_idle(bool idle) { producing_idle_ = idle; }
  bool producing_idle() const { return producing_idle_; }
  // Keying: the device reports this identity instead of its model's.
  void set_identity_override(std::optional<Identity> id) { identity_override_ = std::move(id); }
  // The device's explicit server stops answering (I/O continues).
  void set_explicit_silent(bool silent) { explicit_silent_ = silent; }
  // The device is owned by another master: allocation is refused with an error response.
  void set_owned_elsewhere(bool owned) { owned_elsewhere_ = owned; }
  bool owned_elsewhere() const { return owned_elsewhere_; }

 private:
  CipReply identity_service(const CipRequest& r);
  CipReply devicenet_service(const CipRequest& r);
  CipReply assembly_service(const CipRequest& r);
  CipReply connection_service(const CipRequest& r);
  CipReply parameter_service(const CipRequest& r);
  CipReply vendor_service(ObjectDef& object, const CipRequest& r);
  Bytes identity_attribute(std::uint8_t id) const;
  void apply_action(OutputAction a);
  void notify_input() const {
    if (on_input_change_) on_input_change_();
  }

  DeviceModel model_;
  int mac_ = 63;
  Baud baud_ = Baud::k125;
  bool online_ = true;
  bool allocated_ = false;
  Bytes inputs_;
  Bytes outputs_;
  OutputState output_state_ = OutputState::NotConnected;
  std::vector<std::int64_t> parameter_values_;
  std::vector<ObjectDef> objects_;      // mutable copies of the vendor objects
  std::uint16_t epr_ms_[5] = {0, 0, 0, 0, 0};  // Connection instances 1...4: attribute 9
  std::optional<int> size_override_;
  bool producing_idle_ = false;
  std::optional<Identity> identity_override_;
  bool explicit_silent_ = false;
  bool owned_elsewhere_ = false;
  std::function<void()> on_input_change_;
  std::array<std::uint64_t, 4> consumed_{};
};

}  // namespace softslc::devicenet
