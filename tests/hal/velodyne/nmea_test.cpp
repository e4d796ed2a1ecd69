#include "hal/velodyne/nmea.hpp"

#include <string>

#include <gtest/gtest.h>

namespace flat2d::hal::velodyne {
namespace {

// Days since 1970-01-01 counted the slow way, independent of the parser's closed form.
std::int64_t NaiveDaysSinceEpoch(int year, int month, int day) {
  const auto leap = [](int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; };
  const int month_days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  std::int64_t days = 0;
  for (int y = 1970; y < year; ++y) days += leap(y) ? 366 : 365;
  for (int m = 1; m < month; ++m) days += month_days[m - 1] + (m == 2 && leap(year) ? 1 : 0);
  return days + day - 1;
}

TimeNs Utc(int year, int month, int day, int hour, int minute, int second) {
  return NaiveDaysSinceEpoch(year, month, day) * kNsPerDay +
         ((hour * 60 + minute) * 60 + second) * kNsPerSecond;
}

TEST(Nmea, NaiveDayCountMatchesHandCounts) {
  // 1970-2015: 46 years with 11 leap days (1972..2012), plus 20 days of January 2016.
  EXPECT_EQ(NaiveDaysSinceEpoch(2016, 1, 21), 46 * 365 + 11 + 20);
  // 1970-1993: 24 years with 6 leap days; Jan-Oct 1994 = 304 days; plus 18.
  EXPECT_EQ(NaiveDaysSinceEpoch(1994, 11, 19), 24 * 365 + 6 + 304 + 18);
}

TEST(Nmea, ParsesTheSentenceOfTheMrptVlp16Capture) {
  // Verbatim from the position packets of mrpt_sample_velodyne_vlp16_gps.pcap.
  const auto fix = ParseRmc(
      "$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E\r\n");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_TRUE(fix->has_time);
  EXPECT_EQ(fix->utc_time_ns, Utc(2016, 1, 21, 8, 18, 2));
  EXPECT_EQ(fix->utc_time_ns, 1'453'364'282 * kNsPerSecond);  // the capture's pcap time, 08:18:02
  EXPECT_TRUE(fix->valid);
  EXPECT_EQ(fix->status, 'A');
  EXPECT_EQ(fix->mode, 'A');
  ASSERT_TRUE(fix->has_position);
  EXPECT_NEAR(fix->latitude_deg, 36.0 + 49.7478558 / 60.0, 1e-12);
  EXPECT_NEAR(fix->longitude_deg, -(2.0 + 24.4542928 / 60.0), 1e-12);
  EXPECT_NEAR(fix->speed_mps, 0.034 * 1852.0 / 3600.0, 1e-15);
  EXPECT_DOUBLE_EQ(fix->course_deg, 212.5);
  ASSERT_TRUE(fix->magnetic_variation_deg.has_value());
  EXPECT_DOUBLE_EQ(*fix->magnetic_variation_deg, 0.0);
}

TEST(Nmea, ParsesTheTextbookSentenceWithA19xxYearAndWestVariation) {
  const auto fix =
      ParseRmc("$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*68");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_EQ(fix->utc_time_ns, Utc(1994, 11, 19, 22, 54, 46));
  EXPECT_EQ(fix->utc_time_ns, 785'285'686 * kNsPerSecond);
  EXPECT_NEAR(fix->latitude_deg, 49.0 + 16.45 / 60.0, 1e-12);
  EXPECT_NEAR(fix->longitude_deg, -(123.0 + 11.12 / 60.0), 1e-12);
  EXPECT_NEAR(fix->speed_mps, 0.5 * 0.514444, 1e-6);
  EXPECT_DOUBLE_EQ(fix->course_deg, 54.7);
  EXPECT_DOUBLE_EQ(*fix->magnetic_variation_deg, 20.3);
  EXPECT_EQ(fix->mode, '\0');  // NMEA 2.0: no mode field
  EXPECT_TRUE(fix->valid);
}

TEST(Nmea, ParsesGnrmcWithMillisecondsLeapDaySouthAndNavStatus) {
  const auto fix = ParseRmc(
      "$GNRMC,235959.999,A,3351.1234,S,15112.5000,E,10.0,359.9,290224,,,D,V*21");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_EQ(fix->utc_time_ns, Utc(2024, 2, 29, 23, 59, 59) + 999 * kNsPerMs);
  EXPECT_NEAR(fix->latitude_deg, -(33.0 + 51.1234 / 60.0), 1e-12);
  EXPECT_NEAR(fix->longitude_deg, 151.0 + 12.5 / 60.0, 1e-12);
  EXPECT_FALSE(fix->magnetic_variation_deg.has_value());
  EXPECT_EQ(fix->mode, 'D');
  EXPECT_TRUE(fix->valid);
}

TEST(Nmea, TwoDigitYearsPivotAt80) {
  const auto y1980 =
      ParseRmc("$GPRMC,120000,A,4807.038,N,01131.000,E,022.4,084.4,230380,003.1,W*61");
  ASSERT_TRUE(y1980.ok()) << y1980.error().message;
  EXPECT_EQ(y1980->utc_time_ns, Utc(1980, 3, 23, 12, 0, 0));
  EXPECT_DOUBLE_EQ(*y1980->magnetic_variation_deg, -3.1);
  const auto y2079 =
      ParseRmc("$GPRMC,000000,A,4807.038,N,01131.000,E,022.4,084.4,010179,003.1,W*66");
  ASSERT_TRUE(y2079.ok()) << y2079.error().message;
  EXPECT_EQ(y2079->utc_time_ns, Utc(2079, 1, 1, 0, 0, 0));
}

TEST(Nmea, VoidSentenceWithEmptyFieldsIsNotAnError) {
  const auto fix = ParseRmc("$GPRMC,,V,,,,,,,,,,N*53");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_FALSE(fix->valid);
  EXPECT_FALSE(fix->has_time);
  EXPECT_FALSE(fix->has_position);
  EXPECT_EQ(fix->mode, 'N');
}

TEST(Nmea, VoidSentenceWithTimeButNoDateHasNoTime) {
  const auto fix = ParseRmc("$GPRMC,235947.000,V,,,,,,,,,,N");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_FALSE(fix->has_time);
  // A malformed time is still an error in a void sentence.
  EXPECT_FALSE(ParseRmc("$GPRMC,2359,V,,,,,,,,,,N").ok());
}

TEST(Nmea, ModeNMakesAnActiveFixInvalid) {
  // Checksum left out on purpose: it is optional in NMEA 0183.
  const auto fix = ParseRmc("$GPRMC,120000,A,4807.038,N,01131.000,E,0,0,230394,,,N");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_EQ(fix->status, 'A');
  EXPECT_FALSE(fix->valid);
}

TEST(Nmea, SentenceWithoutChecksumIsAccepted) {
  const auto fix = ParseRmc("$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E");
  ASSERT_TRUE(fix.ok()) << fix.error().message;
  EXPECT_EQ(fix->utc_time_ns, 785'285'686 * kNsPerSecond);
}

struct BadSentence {
  const char* sentence;
  const char* field_in_message;
};

TEST(Nmea, MalformedSentencesNameTheField) {
  const BadSentence cases[] = {
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*69", "checksum"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*6", "checksum"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*G8", "checksum"},
      {"$GPRMC,255446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "time"},
      {"$GPRMC,2254,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "time"},
      {"$GPRMC,225446,X,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "status"},
      {"$GPRMC,225446,A,4976.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "latitude"},
      {"$GPRMC,225446,A,9116.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "latitude"},
      {"$GPRMC,225446,A,49.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "latitude"},
      {"$GPRMC,225446,A,4916.45,Q,12311.12,W,000.5,054.7,191194,020.3,E", "latitude hemisphere"},
      {"$GPRMC,225446,A,4916.45,N,-12311.12,W,000.5,054.7,191194,020.3,E", "longitude"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,,000.5,054.7,191194,020.3,E", "longitude hemisphere"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,1e3,054.7,191194,020.3,E", "speed"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,400,191194,020.3,E", "course"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,310294,020.3,E", "date"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,1911,020.3,E", "date"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,,020.3,E", "date"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,X", "variation"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,,,Z", "mode"},
      {"$GPGGA,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "address"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7", "at least 9"},
      {"GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E", "'$'"},
      {"$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E,A,V,X,Y", "14 fields"},
      {"$GPRMC,225446,A,4916.45,N,\x01" "12311.12,W,000.5,054.7,191194,020.3,E", "non-printable"},
      {"", "'$'"},
  };
  for (const BadSentence& bad : cases) {
    const auto fix = ParseRmc(bad.sentence);
    ASSERT_FALSE(fix.ok()) << "accepted: " << bad.sentence;
    EXPECT_NE(fix.error().message.find(bad.field_in_message), std::string::npos)
        << "sentence: " << bad.sentence << "\nmessage: " << fix.error().message;
  }
}

TEST(Nmea, BadChecksumMessageGivesTheComputedValue) {
  const auto fix =
      ParseRmc("$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*00");
  ASSERT_FALSE(fix.ok());
  EXPECT_NE(fix.error().message.find("computed 68"), std::string::npos) << fix.error().message;
}

TEST(Nmea, IsRmcSentenceChecksOnlyTheAddress) {
  EXPECT_TRUE(IsRmcSentence("$GPRMC,"));
  EXPECT_TRUE(IsRmcSentence("$GNRMC,123"));
  EXPECT_FALSE(IsRmcSentence("$GPGGA,123519,4807.038,N"));
  EXPECT_FALSE(IsRmcSentence("$GPRMC"));
  EXPECT_FALSE(IsRmcSentence(""));
}

}  // namespace
}  // namespace flat2d::hal::velodyne
