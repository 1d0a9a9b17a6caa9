#pragma once
/// @file log_clock.hpp
/// The clocks of the files a vehicle's run leaves behind, so a sonar log and a navigation log
/// recorded by different programs can be put on one time line (docs/formats.md, "Joining a sonar
/// log and a vehicle log").
///
/// Each file's times are seconds on its own clock; what that clock's zero is in UTC, where the
/// file says it: a ROS log's header stamps and a MAVLink telemetry log's time stamps are seconds
/// since 1970 (UTC: zero at 0); a Ping Viewer log's record times are seconds since logging began,
/// which its file name gives in the recording computer's local time (Ping Viewer's FileManager
/// names logs with QDateTime::currentDateTime() formatted `yyyyMMdd-hhmmsszzz`); an ArduSub
/// dataflash log's TimeUS counts from the autopilot's boot, turned into UTC by a GPS fix's week and
/// time of week when it has one. Beam CSVs, navigation CSVs, .mat, SeaNet and raw captures say
/// nothing of their clock.

#include <optional>
#include <string>
#include <string_view>

namespace sonarmap {

/// Seconds east of UTC of a time zone written as `UTC`, `Z`, or an offset `+HH:MM`, `-HH:MM`,
/// `+HHMM`, `+HH` (optionally after `UTC`: `UTC+03:30`); hours ≤ 14, minutes < 60. Named zones
/// (`Asia/Tehran`) are not read: their offset changes with daylight saving, so give the offset in
/// force when the log was recorded.
/// @throws ValueError for any other text, naming the forms accepted.
double parseUtcOffset(std::string_view text);

/// Seconds since 1970-01-01 00:00 of a calendar date and time taken as UTC (proleptic Gregorian
/// calendar, std::chrono's civil calendar). No range check beyond the calendar's own: month 1–12,
/// day valid in its month, hour < 24, minute and second < 60, millisecond < 1000; nullopt otherwise.
std::optional<double> civilSeconds(int year, int month, int day, int hour, int minute, int second, int millisecond);

/// The local date and time a Ping Viewer log's file name starts with (`yyyyMMdd-hhmmsszzz`, e.g.
/// `20240814-101502123.bin`; its digits in any script, as Qt writes them in the recording
/// computer's locale), as seconds since 1970 counted as if that local time were UTC; nullopt
/// when the name does not start that way.
std::optional<double> pingViewerNameTime_s(const std::string& path);

/// `yyyy-mm-dd hh:mm:ss.sss UTC` for seconds since 1970 (UTC), for summaries; "(no clock)" for a
/// non-finite value.
std::string utcText(double utc_s);

}  // namespace sonarmap
