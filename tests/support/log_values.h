// Values and files for the model views' round-trip tests (tests/logs/*_log_test.cc,
// *_reference_test.cc): a ramp with a wobble (no two samples alike), compared to
// the written digits, and a log written to the temporary folder.
#pragma once

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

namespace driveid::testing {

inline std::vector<double> Ramp(std::size_t n, double start, double step) {
  std::vector<double> v;
  for (std::size_t k = 0; k < n; ++k) v.push_back(start + step * static_cast<double>(k) + 1e-3 * std::sin(k));
  return v;
}

inline void CheckClose(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == Approx(b[k]).epsilon(1e-6).margin(1e-9));
}

/// `text` written to a file of the temporary folder, named for the test; its path.
inline std::string WriteTemporary(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / ("driveid_references_" + name);
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace driveid::testing
