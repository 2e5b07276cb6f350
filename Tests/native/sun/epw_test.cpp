// EPW weather files (docs/daylight.md, "Weather"): the Chicago TMY3 file, EN 17037's median
// external diffuse illuminance, and malformed files named by file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "lightsolver/error.hpp"
#include "lightsolver/weather.hpp"

namespace lightsolver {
namespace {

const std::filesystem::path kChicago = std::filesystem::path(LIGHTSOLVER_SOURCE_DIR) /
                                       "Tests/native/sun/data" /
                                       "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";

TEST(Epw, ReadsTheChicagoTmy3File) {
  const WeatherFile w = read_epw(kChicago);
  EXPECT_EQ(w.location.city, "Chicago Ohare Intl Ap");
  EXPECT_EQ(w.location.region, "IL");
  EXPECT_EQ(w.location.country, "USA");
  EXPECT_EQ(w.location.wmo, "725300");
  EXPECT_DOUBLE_EQ(w.location.latitude_deg, 41.98);
  EXPECT_DOUBLE_EQ(w.location.longitude_deg, -87.92);
  EXPECT_DOUBLE_EQ(w.location.utc_offset_h, -6.0);
  EXPECT_DOUBLE_EQ(w.location.elevation_m, 201.0);
  ASSERT_EQ(w.hours.size(), 8760u);
  // 15 July, hour 13 (line 4701 of the file, read by hand).
  const WeatherHour& h = w.hours[(31 + 28 + 31 + 30 + 31 + 30 + 14) * 24 + 12];
  EXPECT_EQ(h.line, 4701);
  EXPECT_EQ(h.month, 7);
  EXPECT_EQ(h.day, 15);
  EXPECT_EQ(h.hour, 13);
  EXPECT_EQ(h.direct_normal_w_m2, 497.0);
  EXPECT_EQ(h.diffuse_horizontal_w_m2, 337.0);
  EXPECT_EQ(h.global_horizontal_lx, 86200.0);
  EXPECT_EQ(h.direct_normal_lx, 52000.0);
  EXPECT_EQ(h.diffuse_horizontal_lx, 37800.0);
  EXPECT_EQ(w.hours.back().month, 12);
  EXPECT_EQ(w.hours.back().day, 31);
  EXPECT_EQ(w.hours.back().hour, 24);
}

// E_v,d,med for Chicago: the median of the brighter 4380 hours' diffuse illuminance. Checked
// outside the solver with the shell: awk -F, 'NR>8{print $19}' FILE | sort -n gives 15900 as its
// 6570th and 6571st values (the middle of the upper half).
TEST(Epw, ChicagoMedianExternalDiffuseIlluminance) {
  EXPECT_DOUBLE_EQ(median_external_diffuse_illuminance(read_epw(kChicago)), 15900.0);
}

// A year of synthetic hours: diffuse illuminance 1, 2, ... 8760 lx in file order, so the
// brighter half is 4381 … 8760 and its median (6570 + 6571) / 2.
std::string synthetic_year(int hours = 8760) {
  std::string s =
      "LOCATION,Testville,,XX,SYN,000000,45.5,7.25,1.0,120.0\n"
      "DESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND TEMPERATURES,0\n"
      "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,synthetic\nCOMMENTS 2,\n"
      "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  int n = 0;
  for (int m = 1; m <= 12; ++m)
    for (int d = 1; d <= kDays[m - 1]; ++d)
      for (int h = 1; h <= 24; ++h) {
        if (++n > hours) return s;
        s += "2001," + std::to_string(m) + "," + std::to_string(d) + "," + std::to_string(h) +
             ",0,flags,10,5,70,101300,0,0,300,0,100,50,9000,4000," + std::to_string(n) +
             ",0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0\n";
      }
  return s;
}

TEST(Epw, MedianOfTheBrighterHalf) {
  const WeatherFile w = parse_epw(synthetic_year(), "syn.epw");
  EXPECT_EQ(w.location.city, "Testville");
  EXPECT_EQ(w.location.region, "");
  EXPECT_DOUBLE_EQ(median_external_diffuse_illuminance(w), 6570.5);
}

// The message of the InputError `text` raises, with its line checked.
std::string epw_error_of(const std::string& text, const std::string& where) {
  try {
    parse_epw(text, "syn.epw");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "syn.epw");
    EXPECT_EQ(e.where(), where) << e.what();
    return e.what();
  }
  return "(no error)";
}

std::string replace_line(std::string text, int line, const std::string& with) {
  size_t start = 0;
  for (int i = 1; i < line; ++i) start = text.find('\n', start) + 1;
  const size_t end = text.find('\n', start);
  return text.replace(start, end - start, with);
}

TEST(Epw, MissingValuesAreAbsentAndStopTheMedian) {
  std::string text = synthetic_year();
  // Line 9 is the first hour: its direct normal irradiance and diffuse illuminance missing.
  text = replace_line(text, 10,
                      "2001,1,1,2,0,flags,10,5,70,101300,0,0,300,0,9999,50,999999,4000,999999,"
                      "0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0");
  const WeatherFile w = parse_epw(text, "syn.epw");
  EXPECT_FALSE(w.hours[1].direct_normal_w_m2.has_value());
  EXPECT_FALSE(w.hours[1].global_horizontal_lx.has_value());
  EXPECT_FALSE(w.hours[1].diffuse_horizontal_lx.has_value());
  EXPECT_EQ(w.hours[1].diffuse_horizontal_w_m2, 50.0);
  try {
    median_external_diffuse_illuminance(w);
    ADD_FAILURE() << "a missing hour must stop the median";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "line 10");
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos);
  }
}

TEST(Epw, MalformedFilesNameFileAndLine) {
  const std::string year = synthetic_year();
  // Truncated: whole rows gone, or the last row cut in the middle.
  EXPECT_NE(epw_error_of(synthetic_year(8000), "line 8008").find("8000 hourly rows"),
            std::string::npos);
  EXPECT_NE(epw_error_of(year.substr(0, year.size() - 40), "line 8768").find("fields"),
            std::string::npos);
  // Wrong field count on a row.
  EXPECT_NE(epw_error_of(replace_line(year, 20, "2001,1,1,12,0,flags,10"), "line 20").find("7"),
            std::string::npos);
  // A value that is not a number, named by its EPW column.
  EXPECT_NE(epw_error_of(replace_line(year, 12,
                                      "2001,1,1,4,0,flags,10,5,70,101300,0,0,300,0,100,50,9000,"
                                      "4000,abc,0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0"),
                         "line 12")
                .find("diffuse horizontal illuminance: 'abc'"),
            std::string::npos);
  // Negative irradiance is out of the dictionary's range.
  EXPECT_NE(epw_error_of(replace_line(year, 12,
                                      "2001,1,1,4,0,flags,10,5,70,101300,0,0,300,0,-5,50,9000,"
                                      "4000,4,0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0"),
                         "line 12")
                .find("direct normal radiation -5"),
            std::string::npos);
  // Rows out of order (an hour skipped).
  EXPECT_NE(epw_error_of(replace_line(year, 12,
                                      "2001,1,1,5,0,flags,10,5,70,101300,0,0,300,0,5,50,9000,"
                                      "4000,4,0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0"),
                         "line 12")
                .find("expected month 1, day 1, hour 4"),
            std::string::npos);
  // A year no int holds.
  EXPECT_NE(epw_error_of(replace_line(year, 12,
                                      "1e300,1,1,4,0,flags,10,5,70,101300,0,0,300,0,5,50,9000,"
                                      "4000,4,0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0"),
                         "line 12")
                .find("year 1e+300"),
            std::string::npos);
  // Month 13.
  EXPECT_NE(epw_error_of(replace_line(year, 12,
                                      "2001,13,1,4,0,flags,10,5,70,101300,0,0,300,0,5,50,9000,"
                                      "4000,4,0,0,0,0,0,0,0,9,0,0,0,0,0,0,0,0"),
                         "line 12")
                .find("month 13"),
            std::string::npos);
  // The LOCATION line: missing, too short, a latitude beyond 90°.
  EXPECT_NE(epw_error_of(replace_line(year, 1, "COMMENTS,x"), "line 1").find("LOCATION"),
            std::string::npos);
  EXPECT_NE(epw_error_of(replace_line(year, 1, "LOCATION,a,b,c"), "line 1").find("10"),
            std::string::npos);
  EXPECT_NE(epw_error_of(replace_line(year, 1, "LOCATION,a,,c,d,1,95,0,0,0"), "line 1")
                .find("latitude 95"),
            std::string::npos);
  // No DATA PERIODS, an empty file.
  EXPECT_NE(
      epw_error_of("LOCATION,a,,c,d,1,45,0,0,0\nCOMMENTS 1,x\n", "line 2").find("DATA PERIODS"),
      std::string::npos);
  EXPECT_NE(epw_error_of("", "").find("empty"), std::string::npos);
}

TEST(Epw, AFileThatCannotBeOpenedIsNamed) {
  try {
    read_epw("/nonexistent/weather.epw");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/weather.epw");
  }
}

}  // namespace
}  // namespace lightsolver
