// What the Modbus TCP and Modbus RTU tests share: the shipped example
// examples/ladder/micrologix/ml1400_batch.slc served with the map B3 (coils and contacts), N7
// (input and holding registers), its io_context on a second thread, and a libmodbus client.
#pragma once

#include <gtest/gtest.h>
#include <modbus.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "server/server.h"

namespace softslc::serve::testing {

inline std::filesystem::path batch_program() {
  return std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/micrologix/ml1400_batch.slc";
}

inline constexpr modbus::Map kBatchMap{3, 3, 7, 7};

class ModbusClientTest : public ::testing::Test {
 protected:
  // Loads the batch program and starts the server with `so` (its EtherNet/IP port and map set
  // here) on a second thread; the caller then opens ctx_.
  void start_server(ServerOptions so, const LiveOptions& lo) {
    live_.emplace(batch_program(), std::nullopt, lo);
    // HIGH_LEVEL (I:0/5): the tank is full, so a batch goes straight to mixing (rungs 1-3).
    live_->controller().set("HIGH_LEVEL", 1);
    so.port = 0;
    so.modbus_map = kBatchMap;
    server_ = std::make_unique<Server>(io_, *live_, so);
    server_->start();
    thread_ = std::thread([this] { io_.run(); });
  }
  void TearDown() override {
    if (ctx_) {
      modbus_close(ctx_);
      modbus_free(ctx_);
    }
    if (!thread_.joinable()) return;
    asio::post(io_, [this] {
      server_->stop();
      io_.stop();
    });
    thread_.join();
  }
  // Runs `f` on the server's thread (the controller is not shared across threads).
  template <typename F>
  auto on_server(F f) {
    std::promise<decltype(f())> done;
    asio::post(io_, [&] { done.set_value(f()); });
    return done.get_future().get();
  }
  std::uint16_t holding(int address) {
    std::uint16_t v = 0xDEAD;
    EXPECT_EQ(modbus_read_registers(ctx_, address, 1, &v), 1) << modbus_strerror(errno);
    return v;
  }
  // The ladder of ml1400_batch.slc responding to a client (start with speed 10: the 2.5 s mix in a
  // quarter of a second): litres per batch (holding 40001 = N7:0 BATCH_L), then BATCH (coil 00002 =
  // B3:0/1) on; the ladder mixes for 2.500 s, adds the volume to TOTAL_L (L9:0, DATA 32500),
  // counts the batch in BATCHES (holding 40002 = N7:1) and unlatches BATCH.
  void run_a_batch() {
    ASSERT_EQ(modbus_write_register(ctx_, 0, 1200), 1);
    ASSERT_EQ(modbus_write_bit(ctx_, 1, 1), 1);
    std::uint16_t batches = 0;
    for (int i = 0; i < 100 && batches == 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      batches = holding(1);
    }
    EXPECT_EQ(batches, 1);
    std::uint8_t batch = 1;
    ASSERT_EQ(modbus_read_bits(ctx_, 1, 1, &batch), 1);
    EXPECT_EQ(batch, 0) << "the finished batch unlatched BATCH";
    EXPECT_EQ(on_server([&] { return live_->controller().get_int("L9:0"); }), 32500 + 1200);
  }
  // The exception code of the last failed request (libmodbus reports it as errno).
  static int exception_of(int rc) {
    if (rc != -1) return 0;
    return errno - MODBUS_ENOBASE;
  }

  asio::io_context io_;
  std::optional<LiveController> live_;
  std::unique_ptr<Server> server_;
  std::thread thread_;
  modbus_t* ctx_ = nullptr;
};

}  // namespace softslc::serve::testing
