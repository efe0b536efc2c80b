// The MicroLogix real-time clock (RTC function file) running in virtual time.
//
// The RTC function file holds the date and time as separate words (YR, MON, DAY, HR, MIN, SEC,
// DOW; rtc:: in parser/address.h, 1762-RM001C p. 3-3 Table 3.2). softslc keeps those words as the
// clock's only state: once per scan the runtime adds the whole seconds of virtual time that
// passed, carrying seconds into minutes, hours, days (with the day of week), months (with their
// lengths and leap years) and years. Because the words are the state, a program (CPW into
// RTC:0.YR, as slc_adjust_clock.RSS does), a `--set RTC:0.HR=23` or a .test SET changes the clock
// and it runs on from the new value. The clock does not run while RTC:0/DS (disabled) is set.
// Words a program has made invalid (MON 13) are not "corrected": the real clock refuses invalid
// data (1766-UM001 ch. 6), softslc only guarantees that advancing them terminates.
#pragma once

#include <cstdint>

namespace softslc {

// Days in `month` (1-12) of `year`; 31 for a month outside 1-12.
int days_in_month(int year, int month);

// Advances the 8 RTC words at `words` by `seconds` (>= 0) of running time.
void advance_real_time_clock(std::uint16_t* words, std::int64_t seconds);

}  // namespace softslc
