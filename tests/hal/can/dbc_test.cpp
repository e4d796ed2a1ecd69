// DBC reader on small inline files: the grammar of BO_/SG_ (Vector DBC spec),
// skipped sections, comments and value tables, multiplexing, and errors that name the
// line and what was expected.
#include "hal/can/dbc.hpp"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace flat2d::hal::can {
namespace {

using ::testing::HasSubstr;

constexpr const char* kHeader = R"(VERSION ""

NS_ :
    NS_DESC_
    CM_
    SG_MUL_VAL_

BS_:

BU_: XXX EON
)";

Dbc Parse(const std::string& text) {
  auto dbc = ParseDbc(text, "test.dbc");
  EXPECT_TRUE(dbc.ok()) << (dbc.ok() ? "" : dbc.error().message);
  return dbc.ok() ? std::move(*dbc) : Dbc{};
}

std::string ErrorOf(const std::string& text) {
  auto dbc = ParseDbc(text, "test.dbc");
  EXPECT_FALSE(dbc.ok());
  return dbc.ok() ? "" : dbc.error().message;
}

TEST(DbcTest, ReadsMessagesAndSignals) {
  const Dbc dbc = Parse(std::string(kHeader) + R"(
BO_ 170 WHEEL_SPEEDS: 8 XXX
 SG_ WHEEL_SPEED_FR : 7|16@0+ (0.01,-67.67) [0|250] "km/h" XXX
 SG_ WHEEL_SPEED_FL : 23|16@0+ (0.01,-67.67) [0|250] "km/h" XXX,EON

BO_ 2566844901 EXTENDED_MSG: 8 EON
  SG_ Temperature : 0|12@1- (1e-2, +250) [-1.5E2|270.47] "degK" EON
)");
  ASSERT_EQ(dbc.messages.size(), 2u);
  const DbcMessage* wheels = dbc.FindMessage(170, false);
  ASSERT_NE(wheels, nullptr);
  EXPECT_EQ(wheels, dbc.FindMessage("WHEEL_SPEEDS"));
  EXPECT_EQ(wheels->dlc, 8);
  EXPECT_EQ(wheels->transmitter, "XXX");
  EXPECT_EQ(wheels->line, 12);
  ASSERT_EQ(wheels->signals.size(), 2u);
  const DbcSignal& fr = wheels->signals[0];
  EXPECT_EQ(fr.name, "WHEEL_SPEED_FR");
  EXPECT_EQ(fr.start_bit, 7);
  EXPECT_EQ(fr.length, 16);
  EXPECT_FALSE(fr.little_endian);
  EXPECT_FALSE(fr.is_signed);
  EXPECT_DOUBLE_EQ(fr.factor, 0.01);
  EXPECT_DOUBLE_EQ(fr.offset, -67.67);
  EXPECT_DOUBLE_EQ(fr.maximum, 250.0);
  EXPECT_EQ(fr.unit, "km/h");
  EXPECT_EQ(fr.line, 13);
  // Bit 31 marks a 29-bit id: 2566844901 = 0x80000000 | 0x18FEF1E5.
  const DbcMessage* extended = dbc.FindMessage(0x18FEF1E5, true);
  ASSERT_NE(extended, nullptr);
  EXPECT_EQ(dbc.FindMessage(0x18FEF1E5, false), nullptr);
  const DbcSignal& temperature = extended->signals.at(0);
  EXPECT_TRUE(temperature.little_endian);
  EXPECT_TRUE(temperature.is_signed);
  EXPECT_DOUBLE_EQ(temperature.factor, 0.01);
  EXPECT_DOUBLE_EQ(temperature.offset, 250.0);
  EXPECT_DOUBLE_EQ(temperature.minimum, -150.0);
  EXPECT_TRUE(dbc.warnings.empty());
}

TEST(DbcTest, KeepsCommentsAndValueNamesAcrossLines) {
  const Dbc dbc = Parse(R"(BO_ 36 KINEMATICS: 8 XXX
 SG_ YAW_RATE : 1|10@0+ (0.244,-125) [0|65535] "deg/s" XXX
 SG_ GEAR : 15|3@0+ (1,0) [0|7] "" XXX

CM_ "BO_ 99 FAKE: 8 XXX
 SG_ X : 0|8@1+ (1,0) [0|0] \"\" XXX";
CM_ SG_ 36 YAW_RATE "verify;
sign convention";
CM_ BO_ 36 "kinematics";
BA_DEF_ SG_ "GenSigStartValue" INT 0 100000;
BA_ "GenMsgCycleTime" BO_ 36 10;
VAL_ 36 GEAR 0 "P" 1 "R" 2 "N" -1 "unknown" ;
VAL_TABLE_ Gears 0 "P" 1 "R" ;
BO_TX_BU_ 36 : XXX,EON;
// a comment line
)");
  ASSERT_EQ(dbc.messages.size(), 1u);  // the BO_ inside the comment string is no message
  const DbcMessage& message = dbc.messages[0];
  EXPECT_EQ(message.comment, "kinematics");
  EXPECT_EQ(message.FindSignal("YAW_RATE")->comment, "verify;\nsign convention");
  const auto& names = message.FindSignal("GEAR")->value_names;
  ASSERT_EQ(names.size(), 4u);
  EXPECT_EQ(names[1].value, 1);
  EXPECT_EQ(names[1].name, "R");
  EXPECT_EQ(names[3].value, -1);
}

TEST(DbcTest, LineNumbersSurviveMultiLineStrings) {
  EXPECT_THAT(ErrorOf("CM_ \"a \\\nb\nc\";\nBO_ 1 A 8 XXX\n"), HasSubstr("test.dbc:4: expected ':'"));
}

TEST(DbcTest, SymbolListMayBeUnindented) {
  const Dbc dbc = Parse("NS_ :\nNS_DESC_\nCM_\nBA_DEF_\n\nBS_:\nBU_: A\nBO_ 1 A: 1 XXX\n");
  EXPECT_EQ(dbc.messages.size(), 1u);
}

TEST(DbcTest, ToleratesLastStatementWithoutSemicolonAndCrLf) {
  const Dbc dbc = Parse("BO_ 1 A: 1 XXX\r\n SG_ B : 0|8@1+ (1,0) [0|0] \"\" XXX\r\n\r\nCM_ \"end\"\r\n");
  ASSERT_EQ(dbc.messages.size(), 1u);
  EXPECT_EQ(dbc.messages[0].signals.at(0).name, "B");
}

TEST(DbcTest, OpendbcIdsAbove11BitsWithoutFlagAreExtendedWithWarning) {
  const Dbc dbc = Parse("BO_ 13274 LKAS_HUD_A: 5 ADAS\n");
  ASSERT_NE(dbc.FindMessage(13274, true), nullptr);
  ASSERT_EQ(dbc.warnings.size(), 1u);
  EXPECT_THAT(dbc.warnings[0], HasSubstr("test.dbc:1"));
}

TEST(DbcTest, SkipsVectorIndependentSignals) {
  const Dbc dbc = Parse(R"(BO_ 3221225472 VECTOR__INDEPENDENT_SIG_MSG: 0 Vector__XXX
 SG_ Orphan : 0|8@1+ (1,0) [0|0] "" Vector__XXX
BO_ 1 A: 1 XXX
)");
  ASSERT_EQ(dbc.messages.size(), 1u);
  EXPECT_EQ(dbc.messages[0].name, "A");
}

TEST(DbcTest, ReadsIeeeValueTypes) {
  const Dbc dbc = Parse(R"(BO_ 1 A: 8 XXX
 SG_ F : 0|32@1- (1,0) [0|0] "" XXX
SIG_VALTYPE_ 1 F : 1;
)");
  EXPECT_EQ(dbc.messages[0].signals[0].value_type, DbcValueType::kFloat32);
  EXPECT_THAT(ErrorOf("BO_ 1 A: 8 XXX\n SG_ F : 0|16@1- (1,0) [0|0] \"\" XXX\nSIG_VALTYPE_ 1 F : 2;\n"),
              HasSubstr("test.dbc:3: SIG_VALTYPE_ F: expected a 64-bit signal"));
}

TEST(DbcTest, SupportsSimpleMultiplexing) {
  // As in strym's TRACK_B_1: names repeat per switch value; the switch may come last.
  const Dbc dbc = Parse(R"(BO_ 401 TRACK_B_1: 8 XXX
 SG_ COUNTER m1: 6|6@0+ (1,0) [0|255] "" XXX
 SG_ SCORE m1 : 22|8@0+ (1,0) [0|100] "" XXX
 SG_ COUNTER m0: 6|6@0+ (1,0) [0|255] "" XXX
 SG_ TRACKB1_mux M : 7|1@0+ (1,0) [0|0] "" XXX, XXX
)");
  const DbcMessage& message = dbc.messages.at(0);
  ASSERT_NE(message.MultiplexSwitch(), nullptr);
  EXPECT_EQ(message.MultiplexSwitch()->name, "TRACKB1_mux");
  EXPECT_EQ(message.signals[0].multiplex, DbcMultiplex::kMultiplexed);
  EXPECT_EQ(message.signals[0].multiplex_value, 1u);
  EXPECT_EQ(message.signals[2].multiplex_value, 0u);
}

TEST(DbcTest, RefusesWhatMultiplexingCannotMean) {
  const std::string message = "BO_ 5 M: 8 XXX\n";
  const std::string switch_s = " SG_ S M : 0|8@1+ (1,0) [0|0] \"\" XXX\n";
  EXPECT_THAT(ErrorOf(message + " SG_ A m1 : 8|8@1+ (1,0) [0|0] \"\" XXX\n\nBO_ 6 N: 8 XXX\n"),
              HasSubstr("test.dbc:2: BO_ M: signal A is multiplexed (m1) but the message has no multiplexer"));
  EXPECT_THAT(ErrorOf(message + switch_s + " SG_ T m1M : 8|8@1+ (1,0) [0|0] \"\" XXX\n"),
              HasSubstr("test.dbc:3: BO_ M: signal T is a multiplexed multiplexer ('m1M'); extended"));
  EXPECT_THAT(ErrorOf(message + switch_s + " SG_ T M : 8|8@1+ (1,0) [0|0] \"\" XXX\n"),
              HasSubstr("test.dbc:3: BO_ M: second multiplexer switch T"));
  EXPECT_THAT(ErrorOf(message + switch_s + " SG_ A m1 : 8|8@1+ (1,0) [0|0] \"\" XXX\n" +
                      " SG_ A m1 : 16|8@1+ (1,0) [0|0] \"\" XXX\n"),
              HasSubstr("test.dbc:4: BO_ M: signal A already defined on line 3"));
  EXPECT_THAT(ErrorOf(message + "SG_MUL_VAL_ 5 A S 1-1;\n"), HasSubstr("test.dbc:2: SG_MUL_VAL_"));
}

struct MalformedCase {
  const char* text;
  const char* message;
};

TEST(DbcTest, MalformedLinesAreNamedWithWhatWasExpected) {
  const MalformedCase cases[] = {
      {"BO_ 1 A: 8 XXX\n SG_ B : 7|16@2+ (1,0) [0|0] \"\" XXX\n",
       "test.dbc:2: BO_ A: signal B: expected byte order 0 (Motorola) or 1 (Intel)"},
      {"BO_ 1 A: 8 XXX\n SG_ B : 7|0@0+ (1,0) [0|0] \"\" XXX\n",
       "test.dbc:2: BO_ A: signal B: expected a length of 1..64"},
      {"BO_ 1 A: 8 XXX\n SG_ B : 7|16@0+ (1;0) [0|0] \"\" XXX\n",
       "test.dbc:2: BO_ A: signal B: expected <factor>,"},
      {"BO_ 1 A: 8 XXX\n SG_ B : 7|16@0+ (1,0) [0|0] km/h XXX\n",
       "signal B: expected the unit as a quoted string"},
      {"BO_ 1 A: 8 XXX\n SG_ B : 7|16@0+ (nan,0) [0|0] \"\" XXX\n", "expected <factor>,"},
      {"\n\nBO_ 1 A 8 XXX\n", "test.dbc:3: expected ':' after the message name"},
      {"BO_ 1 A: 65 XXX\n", "test.dbc:1: expected the message length in bytes (0..64)"},
      {"BO_ 1 A: 2 XXX\n SG_ B : 23|16@0+ (1,0) [0|0] \"\" XXX\n",
       "test.dbc:2: BO_ A: signal B needs 4 bytes; expected it to fit in the message's 2"},
      {" SG_ B : 7|16@0+ (1,0) [0|0] \"\" XXX\n", "test.dbc:1: SG_ outside a message; expected a BO_ line"},
      {"BO_ 1 A: 8 XXX\nBO_ 1 B: 8 XXX\n", "test.dbc:2: BO_ B: id 1 is already used by A (line 1)"},
      {"BO_ 1 A: 8 XXX\nBO_ 2 A: 8 XXX\n", "test.dbc:2: BO_ A: name already used on line 1"},
      {"BO_ 1 A: 8 XXX\n SG_ B : 0|8@1+ (1,0) [0|0] \"\" XXX\n SG_ B : 8|8@1+ (1,0) [0|0] \"\" XXX\n",
       "test.dbc:3: BO_ A: signal B already defined on line 2"},
      {"BO_ 1 A: 8 XXX\nGARBAGE here\n", "test.dbc:2: unexpected 'GARBAGE'; expected a DBC keyword"},
      {"CM_ SG_ 1 B \"never closed;\nBO_ 1 A: 8 XXX\n", "test.dbc:1: string not terminated"},
      {"CM_ SG_ 1 B \"closed\"\nBO_ 1 A: 8 XXX\n", "test.dbc:1: CM_ statement has no ';' before line 2"},
      {"BO_ 4294967296 A: 8 XXX\n", "test.dbc:1: BO_ A: message id 4294967296 is out of range"},
  };
  for (const MalformedCase& entry : cases) {
    EXPECT_THAT(ErrorOf(entry.text), HasSubstr(entry.message)) << entry.text;
  }
}

TEST(DbcTest, LoadDbcNamesMissingFile) {
  auto dbc = LoadDbc("/nonexistent/x.dbc");
  ASSERT_FALSE(dbc.ok());
  EXPECT_THAT(dbc.error().message, HasSubstr("/nonexistent/x.dbc: cannot open"));
}

}  // namespace
}  // namespace flat2d::hal::can
