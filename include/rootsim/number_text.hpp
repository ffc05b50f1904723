#pragma once
// numbers written to be read back (sweep run-folder names and table.csv grid columns, --set values, the
// resolved scene.toml): the shortest text that parses to the same double, so 0.3 reads "0.3" and not
// "0.29999999999999999" as 17 significant digits print it
#include <string>

namespace rootsim {

// shortest round-trip text of x (std::to_chars): "0.3", "35.7", "1e-07", "1e+300"; an integral value
// keeps a ".0" ("2.0", not "2") so that TOML reads it back as a float; "inf", "-inf", "nan" as TOML
// spells them
std::string shortestNumber(double x);
// the shortest round-trip text of x as std::to_chars writes it ("2", "0.3", "1e-07", "nan"): the numbers
// of the CSV and JSON files
std::string numberText(double x);
// the shortest round-trip text of x without an exponent ("0.0000001", "35.7", "2"): for formats whose
// numbers are decimals (RSML's xs:decimal); x must be finite
std::string decimalNumber(double x);

}  // namespace rootsim
