// The tabular method (CIE 190) against published tables of one luminaire whose photometric
// file is public: CIE 190:2010's own example luminaire (data/cie190_example.ldt). Source of
// the file and of both tables: the MIT-licensed test fixtures of eulumdat-core
// (https://github.com/mariusgrote/eulumdat-core, tests/fixtures/ugr/: sample_11.ldt,
// reference/ugr_table_11_cie190.csv, reference/ugr_table_11_Relux.csv), which took them from
// eulumdat-ugr (https://github.com/123VincentB/eulumdat-ugr, MIT). See data/README.md.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "lightsolver/glare.hpp"

namespace lightsolver {
namespace {

using Table = std::array<std::array<double, 10>, 19>;  // rows as kRooms; 5 crosswise, 5 endwise

// CIE 190:2010's UGR table of its example luminaire (S = 1 H, 1000 lm lamp = the file's lamp
// flux, so corrected = uncorrected), one decimal as printed.
constexpr Table kCie190 = {{{8.9, 10.5, 9.3, 10.8, 11.1, 10.7, 12.2, 11.0, 12.5, 12.9},
                            {10.5, 11.9, 10.8, 12.2, 12.6, 12.4, 13.8, 12.8, 14.2, 14.5},
                            {11.0, 12.3, 11.4, 12.6, 13.0, 13.1, 14.5, 13.5, 14.8, 15.2},
                            {11.5, 12.7, 11.9, 13.1, 13.5, 13.6, 14.8, 14.0, 15.2, 15.6},
                            {11.7, 12.9, 12.2, 13.3, 13.7, 13.8, 14.9, 14.2, 15.3, 15.7},
                            {12.0, 13.2, 12.5, 13.5, 14.0, 13.8, 15.0, 14.3, 15.3, 15.8},
                            {9.6, 11.0, 10.0, 11.3, 11.7, 11.0, 12.4, 11.4, 12.7, 13.1},
                            {11.4, 12.5, 11.8, 12.9, 13.3, 13.0, 14.1, 13.4, 14.5, 14.9},
                            {12.0, 13.0, 12.4, 13.4, 13.9, 13.9, 14.9, 14.3, 15.3, 15.7},
                            {12.7, 13.5, 13.1, 14.0, 14.4, 14.5, 15.4, 15.0, 15.8, 16.3},
                            {13.0, 13.8, 13.5, 14.2, 14.7, 14.7, 15.5, 15.2, 16.0, 16.4},
                            {13.4, 14.1, 13.8, 14.6, 15.0, 14.8, 15.6, 15.3, 16.0, 16.5},
                            {12.4, 13.2, 12.8, 13.6, 14.1, 14.0, 14.8, 14.5, 15.3, 15.8},
                            {13.2, 13.8, 13.7, 14.3, 14.8, 14.8, 15.4, 15.3, 15.9, 16.4},
                            {13.6, 14.2, 14.1, 14.7, 15.2, 15.0, 15.6, 15.5, 16.1, 16.6},
                            {14.1, 14.7, 14.6, 15.1, 15.7, 15.2, 15.7, 15.7, 16.2, 16.8},
                            {12.4, 13.1, 12.9, 13.6, 14.1, 14.0, 14.8, 14.5, 15.2, 15.7},
                            {13.2, 13.8, 13.8, 14.3, 14.8, 14.8, 15.4, 15.3, 15.9, 16.4},
                            {13.7, 14.3, 14.3, 14.8, 15.3, 15.1, 15.6, 15.6, 16.1, 16.7}}};

// Relux's table of the same file at the data-sheet spacing S = 0.25 H. Relux prints "<10.0"
// for two cells (2H x 2H, 0.7/0.5/0.2 and 0.5/0.5/0.2 crosswise): stored as 0, checked as a
// bound.
constexpr Table kRelux = {{{0, 11.1, 0, 11.4, 11.8, 11.1, 12.6, 11.4, 13.0, 13.3},
                           {10.8, 12.2, 11.1, 12.5, 12.9, 12.6, 14.0, 12.9, 14.3, 14.7},
                           {11.2, 12.6, 11.6, 12.9, 13.3, 13.2, 14.6, 13.6, 14.9, 15.3},
                           {11.7, 12.9, 12.1, 13.3, 13.7, 13.7, 14.9, 14.1, 15.3, 15.7},
                           {11.9, 13.1, 12.3, 13.5, 13.9, 13.8, 15.0, 14.2, 15.4, 15.8},
                           {12.2, 13.3, 12.6, 13.7, 14.1, 13.8, 15.0, 14.3, 15.4, 15.8},
                           {10.3, 11.7, 10.7, 12.0, 12.4, 11.5, 12.9, 11.9, 13.2, 13.6},
                           {11.7, 12.8, 12.1, 13.2, 13.6, 13.2, 14.4, 13.6, 14.7, 15.2},
                           {12.3, 13.3, 12.7, 13.7, 14.2, 14.0, 15.0, 14.5, 15.5, 15.9},
                           {12.9, 13.8, 13.3, 14.2, 14.7, 14.6, 15.5, 15.1, 16.0, 16.4},
                           {13.2, 14.0, 13.7, 14.5, 14.9, 14.8, 15.6, 15.3, 16.1, 16.5},
                           {13.5, 14.3, 14.0, 14.8, 15.3, 14.9, 15.7, 15.4, 16.1, 16.6},
                           {12.6, 13.5, 13.1, 13.9, 14.4, 14.2, 15.0, 14.6, 15.5, 15.9},
                           {13.3, 14.0, 13.8, 14.5, 15.0, 14.8, 15.5, 15.3, 16.0, 16.5},
                           {13.8, 14.4, 14.3, 14.9, 15.4, 15.1, 15.7, 15.6, 16.2, 16.7},
                           {14.3, 14.8, 14.8, 15.3, 15.8, 15.3, 15.8, 15.8, 16.3, 16.8},
                           {12.7, 13.4, 13.1, 13.9, 14.4, 14.2, 15.0, 14.7, 15.4, 15.9},
                           {13.4, 14.0, 13.9, 14.6, 15.0, 14.9, 15.5, 15.4, 16.0, 16.5},
                           {13.9, 14.4, 14.4, 14.9, 15.4, 15.2, 15.7, 15.7, 16.2, 16.7}}};

UgrTable example_table(double spacing_to_height) {
  UgrTableOptions o;
  o.spacing_to_height = spacing_to_height;
  return ugr_table(load_photometry(std::string(LIGHTSOLVER_SOURCE_DIR) +
                                   "/Tests/native/glare/data/cie190_example.ldt"),
                   o);
}

double cell(const UgrTable& t, int row, int column) {
  const auto& v = column < 5 ? t.rows[row].crosswise[column] : t.rows[row].endwise[column - 5];
  EXPECT_TRUE(v.has_value()) << "row " << row << " column " << column;
  return v.value_or(-1.0);
}

TEST(UgrTableReference, ReproducesCie190sWorkedExampleWithinATenth) {
  // CIE 190 derived its table for S = 1 H. Rounded to one decimal as printed, every one of the
  // 190 values must be within 0.1 of the publication (the unrounded value then lies within
  // 0.15; measured: 0.106 at most, 61 cells one digit off, mean +0.025).
  const UgrTable t = example_table(1.0);
  ASSERT_EQ(t.rows.size(), 19u);
  EXPECT_NEAR(t.lamp_flux_lm, 1000.0, 1e-9);
  for (int r = 0; r < 19; ++r) {
    ASSERT_EQ(t.rows[r].crosswise.size(), 5u);
    for (int c = 0; c < 10; ++c) {
      const double v = cell(t, r, c), printed = std::round(v * 10.0) / 10.0;
      EXPECT_NEAR(printed, kCie190[r][c], 0.1 + 1e-9)
          << "room " << t.rows[r].x_h << "H x " << t.rows[r].y_h << "H, column " << c;
      EXPECT_NEAR(v, kCie190[r][c], 0.15) << "row " << r << " column " << c;
    }
  }
}

TEST(UgrTableReference, MatchesReluxAtTheDataSheetSpacing) {
  // S = 0.25 H, as data sheets print. Relux and this solver both follow CIE 190's formulas;
  // measured: 0.135 at most, rms 0.045. Bound: 0.1 plus the printed value's rounding.
  const UgrTable t = example_table(0.25);
  for (int r = 0; r < 19; ++r) {
    for (int c = 0; c < 10; ++c) {
      const double v = cell(t, r, c);
      if (kRelux[r][c] == 0.0)
        EXPECT_LT(v, 10.0) << "row " << r << " column " << c;  // Relux: "<10.0"
      else
        EXPECT_NEAR(v, kRelux[r][c], 0.15) << "row " << r << " column " << c;
    }
  }
}

}  // namespace
}  // namespace lightsolver
