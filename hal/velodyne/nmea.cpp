#include "hal/velodyne/nmea.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <string>

namespace flat2d::hal::velodyne {
namespace {

constexpr double kKnotsToMps = 1852.0 / 3600.0;  // 1 knot = 1 nautical mile (1852 m) per hour
// $xxRMC plus 13 data fields (NMEA 4.1 adds the navigational status after the mode).
constexpr std::size_t kMaxFields = 14;
constexpr std::size_t kMinFields = 10;  // up to and including the date

enum Field : std::size_t {
  kTime = 1, kStatus, kLatitude, kLatHemisphere, kLongitude, kLonHemisphere, kSpeed, kCourse,
  kDate, kVariation, kVariationDirection, kMode,
};

Error FieldError(std::string_view field, std::string_view value, std::string_view why) {
  return MakeError("RMC " + std::string(field) + " '" + std::string(value) + "': " +
                   std::string(why));
}

bool IsDigits(std::string_view text) {
  if (text.empty()) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// Decimal number without sign or exponent ("12", "12.5", "0.034"), as NMEA writes them.
std::optional<double> ParseUnsigned(std::string_view text) {
  const std::size_t dot = text.find('.');
  const std::string_view whole = text.substr(0, dot);
  const std::string_view fraction = dot == std::string_view::npos ? "" : text.substr(dot + 1);
  if (!whole.empty() && !IsDigits(whole)) return std::nullopt;
  if (!fraction.empty() && !IsDigits(fraction)) return std::nullopt;
  if (whole.empty() && fraction.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

int TwoDigits(std::string_view text, std::size_t pos) {
  return (text[pos] - '0') * 10 + (text[pos + 1] - '0');
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant, "chrono-compatible
// low-level date algorithms", days_from_civil).
std::int64_t DaysFromCivil(int year, int month, int day) {
  year -= month <= 2 ? 1 : 0;
  const int era = (year >= 0 ? year : year - 399) / 400;
  const int year_of_era = year - era * 400;
  const int day_of_year = (153 * (month > 2 ? month - 3 : month + 9) + 2) / 5 + day - 1;
  const int day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
  return static_cast<std::int64_t>(era) * 146097 + day_of_era - 719468;
}

int DaysInMonth(int year, int month) {
  constexpr std::array<int, 12> kDays = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return month == 2 && leap ? 29 : kDays[static_cast<std::size_t>(month - 1)];
}

// hhmmss or hhmmss.f... -> ns since midnight. Second 60 is a leap second.
Result<TimeNs> ParseTimeOfDay(std::string_view text) {
  const bool shape_ok = text.size() >= 6 && IsDigits(text.substr(0, 6)) &&
                        (text.size() == 6 || (text[6] == '.' && text.size() <= 16 &&
                                              (text.size() == 7 || IsDigits(text.substr(7)))));
  if (!shape_ok) return FieldError("time", text, "expected hhmmss or hhmmss.sss");
  const int hours = TwoDigits(text, 0);
  const int minutes = TwoDigits(text, 2);
  const int seconds = TwoDigits(text, 4);
  if (hours > 23 || minutes > 59 || seconds > 60) return FieldError("time", text, "out of range");
  TimeNs fraction_ns = 0;
  TimeNs scale = kNsPerSecond;
  for (std::size_t i = 7; i < text.size(); ++i) {
    scale /= 10;
    fraction_ns += (text[i] - '0') * scale;
  }
  return ((hours * 60 + minutes) * 60 + seconds) * kNsPerSecond + fraction_ns;
}

// ddmmyy -> ns since the epoch at midnight UTC.
Result<TimeNs> ParseDate(std::string_view text) {
  if (text.size() != 6 || !IsDigits(text)) return FieldError("date", text, "expected ddmmyy");
  const int day = TwoDigits(text, 0);
  const int month = TwoDigits(text, 2);
  const int two_digit_year = TwoDigits(text, 4);
  // NMEA has no century: GPS receivers appeared in the 1980s, so 80-99 are 19xx.
  const int year = two_digit_year >= 80 ? 1900 + two_digit_year : 2000 + two_digit_year;
  if (month < 1 || month > 12 || day < 1 || day > DaysInMonth(year, month)) {
    return FieldError("date", text, "no such day");
  }
  return DaysFromCivil(year, month, day) * kNsPerDay;
}

// ddmm.mmmm (latitude) or dddmm.mmmm (longitude) plus hemisphere -> signed degrees. The
// degrees and the minutes are read apart so that no digit is lost to a division.
Result<double> ParseAngle(std::string_view name, std::string_view text,
                          std::string_view hemisphere, int max_degrees, char positive,
                          char negative) {
  const std::size_t dot = std::min(text.find('.'), text.size());
  if (!ParseUnsigned(text) || dot < 3 || dot > 5) {
    return FieldError(name, text, "expected (d)ddmm.mmmm");
  }
  int degrees = 0;
  std::from_chars(text.data(), text.data() + dot - 2, degrees);
  const double minutes = *ParseUnsigned(text.substr(dot - 2));
  if (minutes >= 60.0 || degrees > max_degrees || (degrees == max_degrees && minutes > 0.0)) {
    return FieldError(name, text, "out of range");
  }
  if (hemisphere.size() != 1 || (hemisphere[0] != positive && hemisphere[0] != negative)) {
    return FieldError(std::string(name) + " hemisphere", hemisphere,
                      std::string("expected ") + positive + " or " + negative);
  }
  const double value = degrees + minutes / 60.0;
  return hemisphere[0] == negative ? -value : value;
}

// Checks framing and checksum; returns the text between '$' and '*' (or the line end).
Result<std::string_view> SentenceBody(std::string_view sentence) {
  while (!sentence.empty() && (sentence.back() == '\n' || sentence.back() == '\r')) {
    sentence.remove_suffix(1);
  }
  if (sentence.empty() || sentence.front() != '$') {
    return MakeError("RMC sentence does not start with '$'");
  }
  for (std::size_t i = 0; i < sentence.size(); ++i) {
    const auto c = static_cast<unsigned char>(sentence[i]);
    if (c < 0x20 || c > 0x7E) {
      return MakeError("RMC sentence has a non-printable byte at column " + std::to_string(i));
    }
  }
  const std::size_t star = sentence.find('*');
  std::string_view body = sentence.substr(1, star == std::string_view::npos ? sentence.npos
                                                                               : star - 1);
  if (star == std::string_view::npos) return body;  // checksum is optional in NMEA 0183
  const std::string_view given = sentence.substr(star + 1);
  if (given.size() != 2 || HexDigit(given[0]) < 0 || HexDigit(given[1]) < 0) {
    return FieldError("checksum", given, "expected two hex digits after '*'");
  }
  unsigned computed = 0;
  for (char c : body) computed ^= static_cast<unsigned char>(c);
  const auto expected = static_cast<unsigned>(HexDigit(given[0]) * 16 + HexDigit(given[1]));
  if (computed != expected) {
    constexpr std::string_view kHex = "0123456789ABCDEF";
    const std::string computed_hex = {kHex[computed >> 4], kHex[computed & 15]};
    return FieldError("checksum", given, "mismatch, computed " + computed_hex);
  }
  return body;
}

// Fills time, status, position; the remaining fields are read by ParseRmc.
Status ParseTimeAndPosition(const std::array<std::string_view, kMaxFields>& fields,
                            RmcFix& fix) {
  const std::string_view status = fields[kStatus];
  if (status != "A" && status != "V") return FieldError("status", status, "expected A or V");
  fix.status = status[0];
  const bool void_fix = fix.status == 'V';
  // A void fix may lack time or date (receiver still searching); an active one may not.
  const bool need_time = !void_fix || !fields[kTime].empty();
  const bool need_date = !void_fix || !fields[kDate].empty();
  const Result<TimeNs> time_of_day = need_time ? ParseTimeOfDay(fields[kTime]) : TimeNs{0};
  if (!time_of_day) return time_of_day.error();
  const Result<TimeNs> midnight = need_date ? ParseDate(fields[kDate]) : TimeNs{0};
  if (!midnight) return midnight.error();
  fix.has_time = need_time && need_date;
  fix.utc_time_ns = fix.has_time ? *midnight + *time_of_day : 0;
  if (fields[kLatitude].empty() && fields[kLongitude].empty() && void_fix) return {};
  const Result<double> latitude =
      ParseAngle("latitude", fields[kLatitude], fields[kLatHemisphere], 90, 'N', 'S');
  if (!latitude) return latitude.error();
  const Result<double> longitude =
      ParseAngle("longitude", fields[kLongitude], fields[kLonHemisphere], 180, 'E', 'W');
  if (!longitude) return longitude.error();
  fix.latitude_deg = *latitude;
  fix.longitude_deg = *longitude;
  fix.has_position = true;
  return {};
}

// Speed, course, magnetic variation and mode: all may be empty.
Status ParseMotionAndMode(const std::array<std::string_view, kMaxFields>& fields, RmcFix& fix) {
  if (!fields[kSpeed].empty()) {
    const std::optional<double> knots = ParseUnsigned(fields[kSpeed]);
    if (!knots) return FieldError("speed", fields[kSpeed], "expected knots");
    fix.speed_mps = *knots * kKnotsToMps;
  }
  if (!fields[kCourse].empty()) {
    const std::optional<double> course = ParseUnsigned(fields[kCourse]);
    if (!course || *course > 360.0) return FieldError("course", fields[kCourse], "expected 0-360");
    fix.course_deg = *course;
  }
  if (!fields[kVariation].empty()) {
    const std::optional<double> variation = ParseUnsigned(fields[kVariation]);
    if (!variation || *variation > 180.0) {
      return FieldError("magnetic variation", fields[kVariation], "expected 0-180");
    }
    const std::string_view direction = fields[kVariationDirection];
    if (direction != "E" && direction != "W") {
      return FieldError("magnetic variation direction", direction, "expected E or W");
    }
    fix.magnetic_variation_deg = direction == "W" ? -*variation : *variation;
  }
  const std::string_view mode = fields[kMode];
  if (!mode.empty()) {
    if (mode.size() != 1 || std::string_view("ADEFMNPRS").find(mode[0]) == mode.npos) {
      return FieldError("mode", mode, "expected one of A D E F M N P R S");
    }
    fix.mode = mode[0];
  }
  return {};
}

}  // namespace

bool IsRmcSentence(std::string_view sentence) {
  return sentence.size() >= 7 && sentence[0] == '$' && sentence.substr(3, 4) == "RMC,";
}

Result<RmcFix> ParseRmc(std::string_view sentence) {
  const Result<std::string_view> body = SentenceBody(sentence);
  if (!body) return body.error();
  std::array<std::string_view, kMaxFields> fields{};
  std::size_t count = 0;
  std::string_view rest = *body;
  while (true) {
    if (count == kMaxFields) return MakeError("RMC sentence has more than 14 fields");
    const std::size_t comma = rest.find(',');
    fields[count++] = rest.substr(0, comma);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  const std::string_view address = fields[0];
  if (address.size() != 5 || address.substr(2) != "RMC" || address[0] < 'A' ||
      address[0] > 'Z' || address[1] < 'A' || address[1] > 'Z') {
    return FieldError("address", address, "expected a talker and RMC, e.g. GPRMC");
  }
  if (count < kMinFields) {
    return MakeError("RMC sentence has " + std::to_string(count - 1) +
                     " data fields, expected at least 9 (up to the date)");
  }
  RmcFix fix;
  if (Status status = ParseTimeAndPosition(fields, fix); !status) return status.error();
  if (Status status = ParseMotionAndMode(fields, fix); !status) return status.error();
  fix.valid = fix.status == 'A' && fix.mode != 'N';
  return fix;
}

}  // namespace flat2d::hal::velodyne
