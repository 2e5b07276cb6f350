// Bad files: every failure is an InputError naming the file and the line, never a crash.

#include "photometry_test_util.hpp"

namespace lightsolver {
namespace {

using test::expect_input_error;

// A valid LM-63-2002 file; tests break one line of it (index = line number - 1).
std::vector<std::string> ies_lines() {
  return {"IESNA:LM-63-2002",        // 1
          "[TEST] E",                // 2
          "TILT=NONE",               // 3
          "1 1000 1 3 2 1 2 0 0 0",  // 4: 3 vertical, 2 horizontal angles
          "1 1 10",                  // 5
          "0 45 90",                 // 6
          "0 180",                   // 7
          "100 80 10",               // 8
          "90 70 5"};                // 9
}

PhotometricData parse_ies_lines(const std::vector<std::string>& lines) {
  return parse_ies(test::join_lines(lines), "bad.ies");
}

void expect_ies_error(std::vector<std::string> lines, int line, const std::string& needle) {
  expect_input_error([&] { parse_ies_lines(lines); }, line, needle);
  try {
    parse_ies_lines(lines);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.ies");
  }
}

TEST(IesErrors, BaseFileIsValid) { EXPECT_NO_THROW(parse_ies_lines(ies_lines())); }

TEST(IesErrors, TruncatedData) {
  auto lines = ies_lines();
  lines.pop_back();
  expect_ies_error(lines, 8, "file ends where the candela value should be");
}

TEST(IesErrors, WrongCountsLeaveDataOver) {
  auto lines = ies_lines();
  lines[3] = "1 1000 1 3 1 1 2 0 0 0";  // one horizontal angle claimed, two given
  expect_ies_error(lines, 8, "unexpected data after the candela table");
}

TEST(IesErrors, NonMonotonicAngles) {
  auto lines = ies_lines();
  lines[5] = "0 90 45";
  expect_ies_error(lines, 6, "vertical angles must increase");
  lines = ies_lines();
  lines[5] = "0 45 45";
  expect_ies_error(lines, 6, "must increase");
}

TEST(IesErrors, NegativeCandela) {
  auto lines = ies_lines();
  lines[7] = "100 -80 10";
  expect_ies_error(lines, 8, "candela values must be >= 0");
}

TEST(IesErrors, UnknownPhotometricType) {
  auto lines = ies_lines();
  lines[3] = "1 1000 1 3 2 4 2 0 0 0";
  expect_ies_error(lines, 4, "unknown photometric type");
}

TEST(IesErrors, MissingTiltLine) {
  auto lines = ies_lines();
  lines.erase(lines.begin() + 2);
  expect_ies_error(lines, 8, "missing TILT= line");
}

TEST(IesErrors, NotANumber) {
  auto lines = ies_lines();
  lines[7] = "100 nan 10";
  expect_ies_error(lines, 8, "'nan' is not a finite number");
  lines[7] = "100 inf 10";
  expect_ies_error(lines, 8, "is not a finite number");
  lines[7] = "100 8O 10";  // letter O typed for a zero
  expect_ies_error(lines, 8, "'8O' is not a finite number");
}

TEST(IesErrors, AbsurdCountsAreRefusedBeforeReading) {
  auto lines = ies_lines();
  lines[3] = "1 1000 1 2000000 2 1 2 0 0 0";
  expect_ies_error(lines, 4, "number of vertical angles must be between 2 and 1000000");
  lines[3] = "1 1000 1 2000 2000 1 2 0 0 0";
  expect_ies_error(lines, 4, "larger than the 1000000 accepted");
  lines[3] = "1 1000 1 2.5 2 1 2 0 0 0";
  expect_ies_error(lines, 4, "must be a whole number");
}

TEST(IesErrors, AnglesOutOfRange) {
  auto lines = ies_lines();
  lines[5] = "0 45 190";
  expect_ies_error(lines, 6, "outside 0");
  lines = ies_lines();
  lines[6] = "0 120";
  expect_ies_error(lines, 7, "horizontal angles must run");
}

TEST(IesErrors, BadHeaderValues) {
  auto lines = ies_lines();
  lines[3] = "1 0 1 3 2 1 2 0 0 0";
  expect_ies_error(lines, 4, "lumens per lamp must be > 0, or -1");
  lines[3] = "1 1000 0 3 2 1 2 0 0 0";
  expect_ies_error(lines, 4, "candela multiplier must be > 0");
  lines[3] = "1 1000 1 3 2 1 3 0 0 0";
  expect_ies_error(lines, 4, "units type must be 1");
  lines = ies_lines();
  lines[4] = "0 1 10";
  expect_ies_error(lines, 5, "ballast factor must be > 0");
  lines = ies_lines();
  lines[2] = "TILT=";
  expect_ies_error(lines, 3, "TILT= needs");
  lines[0] = "IES:LM-63-2019";
  lines[2] = "TILT=lamp.tlt";
  expect_ies_error(lines, 3, "LM-63-2019 allows only");
}

TEST(IesErrors, BadTiltTable) {
  auto lines = ies_lines();
  lines[2] = "TILT=INCLUDE";
  lines.insert(lines.begin() + 3, {"1", "3", "0 45 30", "1 1 1"});
  expect_ies_error(lines, 6, "TILT angles must increase");
  lines[5] = "0 30 45";
  lines[6] = "1 -1 1";
  expect_ies_error(lines, 7, "TILT multiplying factors must be >= 0");
}

TEST(IesErrors, EmptyAndMissingFiles) {
  expect_input_error([] { parse_ies("", "empty.ies"); }, 1, "empty file");
  expect_input_error([] { load_photometry("/nonexistent/lum.ies"); }, 0, "cannot open file");
}

// A valid EULUMDAT file (Isym 2, Mc 4, Ng 3) as lines; tests break one of them.
std::vector<std::string> ldt_lines() {
  std::vector<std::string> l{"Co", "1", "2", "4", "90", "3", "45", "r", "n", "c", "f", "d"};
  for (int k = 0; k < 9; ++k) l.push_back("0");  // lines 13-21: sizes
  for (const char* v : {"100", "100", "1", "0", "1", "1", "LED", "1000", "3000", "80", "10"})
    l.push_back(v);                                                // lines 22-32
  for (int k = 0; k < 10; ++k) l.push_back("0");                   // 33-42: direct ratios
  for (const char* v : {"0", "90", "180", "270"}) l.push_back(v);  // 43-46: C angles
  for (const char* v : {"0", "45", "90"}) l.push_back(v);          // 47-49: gamma angles
  for (const char* v : {"300", "200", "10", "250", "150", "5", "200", "100", "0"})
    l.push_back(v);  // 50-58
  return l;
}

void expect_ldt_error(const std::vector<std::string>& lines, int line, const std::string& needle) {
  expect_input_error([&] { parse_ldt(test::join_lines(lines), "bad.ldt"); }, line, needle);
}

TEST(LdtErrors, BaseFileIsValid) {
  const auto d = parse_ldt(test::join_lines(ldt_lines()), "ok.ldt");
  EXPECT_DOUBLE_EQ(d.candela_at(3, 0), 250.0);  // C270 = C90
}

TEST(LdtErrors, TruncatedData) {
  auto lines = ldt_lines();
  lines.resize(55);
  expect_ldt_error(lines, 55, "file ends where the luminous intensity should be");
}

TEST(LdtErrors, WrongCounts) {
  auto lines = ldt_lines();
  lines[5] = "2";  // Ng 2 but three gamma angles follow: 3 values are left over
  expect_ldt_error(lines, 55, "unexpected data after the intensity table");
}

TEST(LdtErrors, NonMonotonicAngles) {
  auto lines = ldt_lines();
  lines[47] = "0";  // gamma 0, 0, 90
  expect_ldt_error(lines, 48, "gamma angles must increase");
}

TEST(LdtErrors, NegativeIntensity) {
  auto lines = ldt_lines();
  lines[52] = "-5";
  expect_ldt_error(lines, 53, "luminous intensities must be >= 0");
}

TEST(LdtErrors, BadSymmetryIndicatorAndPlanes) {
  auto lines = ldt_lines();
  lines[2] = "5";
  expect_ldt_error(lines, 3, "symmetry indicator Isym must be a whole number in 0..4");
  lines[2] = "2";
  lines[44] = "170";  // C(Mc/2) must be 180 for Isym 2
  expect_ldt_error(lines, 46, "Isym 2");
}

TEST(LdtErrors, NotANumberAndAbsurdCounts) {
  auto lines = ldt_lines();
  lines[50] = "NaN";
  expect_ldt_error(lines, 51, "not a finite number");
  lines = ldt_lines();
  lines[3] = "1000000";
  expect_ldt_error(lines, 4, "number of C planes Mc must be a whole number in 1..100000");
  lines[3] = "4";
  lines[5] = "99999";
  lines[2] = "0";
  lines[3] = "40000";
  expect_ldt_error(lines, 47, "C angles must increase");  // runs into the gamma angles
}

TEST(LdtErrors, NoLampFlux) {
  auto lines = ldt_lines();
  lines[28] = "0";
  expect_ldt_error(lines, 29, "lamp flux must be > 0");
}

}  // namespace
}  // namespace lightsolver
