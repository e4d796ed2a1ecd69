#include "hal/velodyne/position_packet_encoder.hpp"

#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include "hal/common/time.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr double kMpsToKnots = 3600.0 / 1852.0;  // 1 knot = 1852 m per hour
constexpr double kMaxKnots = 99999.0;            // bounds the sentence length

std::int64_t Pow10(int exponent) {
  std::int64_t value = 1;
  for (int i = 0; i < exponent; ++i) value *= 10;
  return value;
}

// Writes ASCII into the sentence region of the packet. The region (306 bytes) exceeds the
// longest sentence that validated content produces (about 115 bytes), so `fits` stays true.
class SentenceWriter {
 public:
  SentenceWriter(std::uint8_t* begin, std::uint8_t* end) : begin_(begin), pos_(begin), end_(end) {}

  void Put(char c) {
    if (pos_ == end_) {
      fits_ = false;
      return;
    }
    *pos_++ = static_cast<std::uint8_t>(c);
  }
  void Text(std::string_view text) {
    for (char c : text) Put(c);
  }
  // Zero-padded to `width` digits (at least); value >= 0.
  void Digits(std::int64_t value, int width) {
    std::array<char, 20> reversed{};
    int count = 0;
    do {
      reversed[static_cast<std::size_t>(count++)] = static_cast<char>('0' + value % 10);
      value /= 10;
    } while (value > 0 || count < width);
    while (count > 0) Put(reversed[static_cast<std::size_t>(--count)]);
  }
  // `units` in 10^-decimals, written as whole.fraction; whole part padded to `width`.
  void Fixed(std::int64_t units, int decimals, int width) {
    const std::int64_t scale = Pow10(decimals);
    Digits(units / scale, width);
    if (decimals == 0) return;
    Put('.');
    Digits(units % scale, decimals);
  }
  // XOR of every character after '$' written so far (NMEA 0183 checksum).
  unsigned Checksum() const {
    unsigned sum = 0;
    for (const std::uint8_t* p = begin_ + 1; p < pos_; ++p) sum ^= *p;
    return sum;
  }
  bool fits() const { return fits_; }

 private:
  std::uint8_t* begin_;
  std::uint8_t* pos_;
  std::uint8_t* end_;
  bool fits_ = true;
};

// Civil date of a day count since 1970-01-01 (H. Hinnant, civil_from_days).
void CivilFromDays(std::int64_t days, int& year, int& month, int& day) {
  days += 719468;
  const std::int64_t era = (days >= 0 ? days : days - 146096) / 146097;
  const auto day_of_era = static_cast<int>(days - era * 146097);
  const int year_of_era =
      (day_of_era - day_of_era / 1460 + day_of_era / 36524 - day_of_era / 146096) / 365;
  const int day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
  const int mp = (5 * day_of_year + 2) / 153;
  day = day_of_year - (153 * mp + 2) / 5 + 1;
  month = mp < 10 ? mp + 3 : mp - 9;
  year = static_cast<int>(year_of_era + era * 400) + (month <= 2 ? 1 : 0);
}

bool InRange(double value, double low, double high) {
  return std::isfinite(value) && value >= low && value <= high;
}

Status ValidateFix(const RmcFix& fix, const RmcFormat& format) {
  const auto bad = [](std::string_view what) {
    return MakeError("position packet RMC: " + std::string(what));
  };
  if (fix.status != 'A' && fix.status != 'V') return bad("status must be 'A' or 'V'");
  if (fix.status == 'A' && (!fix.has_time || !fix.has_position)) {
    return bad("an active ('A') fix needs time, date and position");
  }
  if (fix.has_time && (fix.utc_time_ns < 315'532'800 * kNsPerSecond ||      // 1980-01-01
                       fix.utc_time_ns >= 3'471'292'800 * kNsPerSecond)) {  // 2080-01-01
    return bad("UTC time outside 1980-2079, which a two-digit NMEA year cannot carry");
  }
  if (fix.has_position && (!InRange(fix.latitude_deg, -90.0, 90.0) ||
                           !InRange(fix.longitude_deg, -180.0, 180.0))) {
    return bad("latitude beyond 90 or longitude beyond 180 degrees");
  }
  if (!InRange(fix.speed_mps * kMpsToKnots, 0.0, kMaxKnots)) return bad("speed out of range");
  if (!InRange(fix.course_deg, 0.0, 360.0)) return bad("course outside 0-360 degrees");
  if (fix.magnetic_variation_deg && !InRange(*fix.magnetic_variation_deg, -180.0, 180.0)) {
    return bad("magnetic variation beyond 180 degrees");
  }
  if (fix.mode != '\0' && std::string_view("ADEFMNPRS").find(fix.mode) == std::string_view::npos) {
    return bad("mode must be one of A D E F M N P R S or absent");
  }
  const auto decimals_ok = [](int d, int max) { return d >= 0 && d <= max; };
  if (!decimals_ok(format.time_decimals, 9) || !decimals_ok(format.minute_decimals, 9) ||
      !decimals_ok(format.speed_decimals, 6) || !decimals_ok(format.course_decimals, 6) ||
      !decimals_ok(format.variation_decimals, 6)) {
    return bad("decimal places out of range (time and minutes 0-9, others 0-6)");
  }
  if (format.speed_digits < 1 || format.speed_digits > 5 || format.course_digits < 1 ||
      format.course_digits > 3 || format.variation_digits < 1 || format.variation_digits > 3) {
    return bad("integer digits out of range (speed 1-5, course and variation 1-3)");
  }
  for (char c : format.talker) {
    if (c < 'A' || c > 'Z') return bad("talker must be two upper-case letters");
  }
  return {};
}

void WriteTime(SentenceWriter& out, TimeNs utc_time_ns, int decimals) {
  const TimeNs of_day = utc_time_ns % kNsPerDay;
  const TimeNs seconds = of_day / kNsPerSecond;
  out.Digits(seconds / 3600, 2);
  out.Digits(seconds / 60 % 60, 2);
  // Truncated, not rounded: rounding could carry into the next day and change the date.
  out.Fixed((seconds % 60) * Pow10(decimals) + (of_day % kNsPerSecond) / Pow10(9 - decimals),
            decimals, 2);
}

void WriteDate(SentenceWriter& out, TimeNs utc_time_ns) {
  int year = 0, month = 0, day = 0;
  CivilFromDays(utc_time_ns / kNsPerDay, year, month, day);
  out.Digits(day, 2);
  out.Digits(month, 2);
  out.Digits(year % 100, 2);
}

// (d)ddmm.mmm... then the hemisphere; rounded in integer minutes so that 59.99999 minutes
// carry into the degrees instead of printing "60".
void WriteAngle(SentenceWriter& out, double degrees, int degree_digits, int decimals,
                char positive, char negative) {
  const std::int64_t scale = Pow10(decimals);
  const auto units = static_cast<std::int64_t>(std::llround(std::abs(degrees) * 60.0 * scale));
  out.Digits(units / (60 * scale), degree_digits);
  out.Fixed(units % (60 * scale), decimals, 2);
  out.Put(',');
  out.Put(degrees < 0.0 ? negative : positive);
}

void WriteDecimal(SentenceWriter& out, double value, int decimals, int digits) {
  out.Fixed(static_cast<std::int64_t>(std::llround(value * static_cast<double>(Pow10(decimals)))),
            decimals, digits);
}

void WriteRmc(SentenceWriter& out, const RmcFix& fix, const RmcFormat& format) {
  out.Put('$');
  out.Put(format.talker[0]);
  out.Put(format.talker[1]);
  out.Text("RMC,");
  if (fix.has_time) WriteTime(out, fix.utc_time_ns, format.time_decimals);
  out.Put(',');
  out.Put(fix.status);
  out.Put(',');
  if (fix.has_position) {
    WriteAngle(out, fix.latitude_deg, 2, format.minute_decimals, 'N', 'S');
    out.Put(',');
    WriteAngle(out, fix.longitude_deg, 3, format.minute_decimals, 'E', 'W');
  } else {
    out.Text(",,");
  }
  out.Put(',');
  WriteDecimal(out, fix.speed_mps * kMpsToKnots, format.speed_decimals, format.speed_digits);
  out.Put(',');
  WriteDecimal(out, fix.course_deg, format.course_decimals, format.course_digits);
  out.Put(',');
  if (fix.has_time) WriteDate(out, fix.utc_time_ns);
  out.Put(',');
  if (fix.magnetic_variation_deg) {
    WriteDecimal(out, std::abs(*fix.magnetic_variation_deg), format.variation_decimals,
                 format.variation_digits);
    out.Put(',');
    out.Put(*fix.magnetic_variation_deg < 0.0 ? 'W' : 'E');
  } else {
    out.Put(',');
  }
  if (fix.mode != '\0') {
    out.Put(',');
    out.Put(fix.mode);
  }
  constexpr std::string_view kHex = "0123456789ABCDEF";
  const unsigned checksum = out.Checksum();
  out.Put('*');
  out.Put(kHex[checksum >> 4]);
  out.Put(kHex[checksum & 15]);
  out.Text("\r\n");
}

}  // namespace

Result<PositionPacketBytes> EncodePositionPacket(const PositionPacketContent& content) {
  if (content.us_past_hour >= kUsPerHour) {
    return MakeError("position packet: timestamp " + std::to_string(content.us_past_hour) +
                     " us is an hour or more");
  }
  if (static_cast<std::uint8_t>(content.pps_status) >
      static_cast<std::uint8_t>(PpsStatus::kError)) {
    return MakeError("position packet: PPS status must be 0-3");
  }
  if (content.rmc) {
    if (Status status = ValidateFix(*content.rmc, content.format); !status) return status.error();
  }
  PositionPacketBytes bytes{};
  for (int i = 0; i < 4; ++i) {
    bytes[kPositionTimestampOffset + static_cast<std::size_t>(i)] =
        static_cast<std::uint8_t>(content.us_past_hour >> (8 * i));
  }
  bytes[kPositionPpsStatusOffset] = static_cast<std::uint8_t>(content.pps_status);
  if (content.rmc) {
    // One NUL must follow CR/LF, so the writer stops a byte before the end.
    SentenceWriter out(bytes.data() + kPositionNmeaOffset, bytes.data() + bytes.size() - 1);
    WriteRmc(out, *content.rmc, content.format);
    if (!out.fits()) return MakeError("position packet: RMC sentence longer than 305 bytes");
  }
  return bytes;
}

}  // namespace flat2d::hal::velodyne
