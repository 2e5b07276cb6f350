#pragma once
/// \file weather.hpp
/// Weather files (docs/daylight.md, "Weather"): the EnergyPlus weather format (EPW), its location
/// and hourly daylight columns, and the median external diffuse illuminance EN 17037 needs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lightsolver {

/// The LOCATION line of a weather file.
struct WeatherLocation {
  std::string city, region, country;  ///< as written (region may be empty)
  std::string source;                 ///< the data set ("TMY3", "IWEC", ...)
  std::string wmo;                    ///< the station's WMO number, as written
  double latitude_deg = 0.0;          ///< −90 … 90, north positive
  double longitude_deg = 0.0;         ///< −180 … 180, east positive
  double utc_offset_h = 0.0;          ///< the file's standard time zone, −12 … 14 h
  double elevation_m = 0.0;           ///< −1000 … 9999.9 m
};

/// One hourly row's daylight columns. EPW marks a missing value by a number at or above its
/// field's limit (9999 for irradiance, 999900 for illuminance): such a value is absent here.
struct WeatherHour {
  int year = 0, month = 1, day = 1;
  int hour = 1;  ///< 1 … 24: the row describes the hour that ends at this time (standard time)
  std::optional<double> direct_normal_w_m2;       ///< direct normal irradiance
  std::optional<double> diffuse_horizontal_w_m2;  ///< diffuse horizontal irradiance
  std::optional<double> global_horizontal_lx;     ///< global horizontal illuminance
  std::optional<double> direct_normal_lx;         ///< direct normal illuminance
  std::optional<double> diffuse_horizontal_lx;    ///< diffuse horizontal illuminance
  int line = 0;                                   ///< the row's line in the file (1-based)
};

/// A weather file read whole.
struct WeatherFile {
  std::string file;  ///< the name errors use
  WeatherLocation location;
  std::vector<WeatherHour> hours;  ///< 8760 rows (8784 when the file declares a leap year)
};

/// Reads an EPW file. InputError naming the file and the line (and the column, by EPW's field
/// name) for a missing LOCATION line, a row with other than 35 fields, a value that is not a
/// number or is out of the dictionary's range, rows out of order, or a file shorter or longer
/// than a year of hours.
WeatherFile read_epw(const std::filesystem::path& path);

/// The same from text in memory; `file` names it in errors.
WeatherFile parse_epw(std::string_view text, const std::string& file);

/// EN 17037's daylight hours of a year: the half of its hours (⌊n/2⌋, 4380 of 8760) with the
/// highest diffuse horizontal illuminance (lx, one value per hour), as a mask (1: a daylight
/// hour); ties at the boundary go to the earlier hour. InputError naming
/// `diffuse_horizontal_lx[i]` for a negative or non-finite value, and for fewer than 2 hours.
std::vector<std::uint8_t> en17037_daylight_hours(const std::vector<double>& diffuse_horizontal_lx);

/// EN 17037's median external diffuse horizontal illuminance E_v,d,med (lx) from a year of
/// hours: the median over its daylight hours, which EN 17037 takes as the half of the year's
/// hours (4380 of 8760) with the highest diffuse horizontal illuminance (en17037_daylight_hours;
/// so it is the year's 75th percentile). InputError naming the file and line of the first hour
/// whose diffuse illuminance is missing.
double median_external_diffuse_illuminance(const WeatherFile& weather);

}  // namespace lightsolver
