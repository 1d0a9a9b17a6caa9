/// @file log_clock.cpp
/// parseUtcOffset, civilSeconds, pingViewerNameTime_s, utcText (see log_clock.hpp).

#include "sonarmap/formats/log_clock.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "sonarmap/core/errors.hpp"
#include "ping_viewer_time.hpp"

namespace sonarmap {
namespace {

/// The value of `count` ASCII digits at `text[at]`, or nullopt.
std::optional<int> digitsAt(std::string_view text, std::size_t at, std::size_t count) {
  if (at + count > text.size()) return std::nullopt;
  int value = 0;
  for (std::size_t i = at; i < at + count; ++i) {
    if (text[i] < '0' || text[i] > '9') return std::nullopt;
    value = value * 10 + (text[i] - '0');
  }
  return value;
}

}  // namespace

double parseUtcOffset(std::string_view text) {
  const auto bad = [&text] {
    return ValueError("time zone '" + std::string(text) +
                      "': expected UTC, Z or an offset from UTC such as +03:30, -05:00, +0530 or +02");
  };
  std::string_view rest = text;
  if (rest.empty()) throw bad();
  if (rest.starts_with("UTC") || rest.starts_with("utc")) rest.remove_prefix(3);
  if (rest.empty() || rest == "Z" || rest == "z") return 0.0;
  if (rest[0] != '+' && rest[0] != '-') throw bad();
  const double sign = rest[0] == '-' ? -1.0 : 1.0;
  rest.remove_prefix(1);
  std::optional<int> hours, minutes = 0;
  if (rest.size() == 2) {
    hours = digitsAt(rest, 0, 2);
  } else if (rest.size() == 4) {
    hours = digitsAt(rest, 0, 2);
    minutes = digitsAt(rest, 2, 2);
  } else if (rest.size() == 5 && rest[2] == ':') {
    hours = digitsAt(rest, 0, 2);
    minutes = digitsAt(rest, 3, 2);
  }
  if (!hours || !minutes || *hours > 14 || *minutes > 59) throw bad();
  return sign * (*hours * 3600.0 + *minutes * 60.0);
}

std::optional<double> civilSeconds(int year, int month, int day, int hour, int minute, int second, int millisecond) {
  using namespace std::chrono;
  const year_month_day date{std::chrono::year{year}, std::chrono::month{static_cast<unsigned>(month)},
                            std::chrono::day{static_cast<unsigned>(day)}};
  if (!date.ok() || hour < 0 || hour > 23 || minute < 0 || minute > 59 || second < 0 || second > 59 ||
      millisecond < 0 || millisecond > 999) {
    return std::nullopt;
  }
  const double days_since_1970 = static_cast<double>(sys_days{date}.time_since_epoch().count());
  return days_since_1970 * 86400.0 + hour * 3600.0 + minute * 60.0 + second + millisecond / 1000.0;
}

std::optional<double> pingViewerNameTime_s(const std::string& path) {
  const std::string name = detail::asciiDigits(std::filesystem::path(path).filename().string());
  // yyyyMMdd-hhmmsszzz: 8 digits, '-', 9 digits
  if (name.size() < 18 || name[8] != '-') return std::nullopt;
  const auto year = digitsAt(name, 0, 4), month = digitsAt(name, 4, 2), day = digitsAt(name, 6, 2);
  const auto hour = digitsAt(name, 9, 2), minute = digitsAt(name, 11, 2), second = digitsAt(name, 13, 2);
  const auto millisecond = digitsAt(name, 15, 3);
  if (!year || !month || !day || !hour || !minute || !second || !millisecond) return std::nullopt;
  if (name.size() > 18 && name[18] >= '0' && name[18] <= '9') return std::nullopt;  // more digits: another name
  return civilSeconds(*year, *month, *day, *hour, *minute, *second, *millisecond);
}

std::string utcText(double utc_s) {
  if (!std::isfinite(utc_s)) return "(no clock)";
  using namespace std::chrono;
  const long long total_ms = std::llround(utc_s * 1000.0);
  const long long ms_per_day = 86400000LL;
  const long long day = (total_ms >= 0 ? total_ms : total_ms - ms_per_day + 1) / ms_per_day;
  long long ms_of_day = total_ms - day * ms_per_day;
  const year_month_day date{sys_days{days{day}}};
  const long long hour = ms_of_day / 3600000LL;
  ms_of_day -= hour * 3600000LL;
  const long long minute = ms_of_day / 60000LL;
  ms_of_day -= minute * 60000LL;
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02u-%02u %02lld:%02lld:%02lld.%03lld UTC", static_cast<int>(date.year()),
                static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()), hour, minute, ms_of_day / 1000,
                ms_of_day % 1000);
  return text;
}

}  // namespace sonarmap
