// A user's ladder test with the softslc C++ API: the seal-in example's start/stop behaviour.
#include <gtest/gtest.h>

#include "tools/controller/controller.h"

TEST(SealIn, StartSealsInAndStopDropsOut) {
  softslc::Controller plc = softslc::Controller::load(SEAL_IN);
  plc.scan();  // first pass
  plc.set("START_PB", 1);
  plc.scan();
  plc.set("START_PB", 0);
  plc.scan();
  EXPECT_TRUE(plc.get_bit("MOTOR"));
  plc.set("STOP_PB", 1);
  plc.scan();
  EXPECT_FALSE(plc.get_bit("MOTOR"));
}
