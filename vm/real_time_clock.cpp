#include "vm/real_time_clock.h"

#include "parser/address.h"

namespace softslc {

int days_in_month(int year, int month) {
  switch (month) {
    case 4:
    case 6:
    case 9:
    case 11: return 30;
    case 2: {
      const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
      return leap ? 29 : 28;
    }
    default: return 31;
  }
}

void advance_real_time_clock(std::uint16_t* w, std::int64_t seconds) {
  if (seconds <= 0 || (w[rtc::kStatusWord] >> rtc::kDisabledBit) & 1u) return;
  auto get = [&](int i) { return static_cast<std::int64_t>(static_cast<std::int16_t>(w[i])); };
  auto put = [&](int i, std::int64_t v) { w[i] = static_cast<std::uint16_t>(v); };
  // Seconds of the day so far, plus the elapsed time, split into whole days and the time of day.
  std::int64_t of_day = get(rtc::kHour) * 3600 + get(rtc::kMinute) * 60 + get(rtc::kSecond) + seconds;
  std::int64_t days = of_day / 86400;
  of_day %= 86400;
  if (of_day < 0) {  // a negative word written by the program
    of_day += 86400;
    days -= 1;
  }
  put(rtc::kHour, of_day / 3600);
  put(rtc::kMinute, of_day / 60 % 60);
  put(rtc::kSecond, of_day % 60);
  if (days <= 0) return;
  put(rtc::kDayOfWeek, ((get(rtc::kDayOfWeek) % 7 + 7) % 7 + days % 7) % 7);
  std::int64_t year = get(rtc::kYear), month = get(rtc::kMonth), day = get(rtc::kDay);
  // One month per iteration: at most one per 28 days of elapsed time, plus one for a day word
  // beyond its month.
  while (days > 0) {
    const int length = days_in_month(static_cast<int>(year), static_cast<int>(month));
    const std::int64_t left_in_month = day < length ? length - day : 0;
    if (days <= left_in_month) {
      day += days;
      break;
    }
    days -= left_in_month + 1;
    day = 1;
    if (++month > 12 || month < 1) {
      month = 1;
      ++year;
    }
  }
  put(rtc::kYear, year);
  put(rtc::kMonth, month);
  put(rtc::kDay, day);
}

}  // namespace softslc
