// A small MAT file written by matio (independent of the reader under test)
// for the log-input tests: `time` 1 x 5, `data` 5 x 3 (compressed), scalar
// `gain`, struct `rec` (pos 2 x 5, time_cont 5 x 1), complex `z`.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <matio.h>
#include <unistd.h>

namespace driveid::testing {

inline std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A MAT file written by matio (independent of the reader under test).
// Writes one variable and frees it.
inline void Put(mat_t* mat, matvar_t* var, matio_compression compression = MAT_COMPRESSION_NONE) {
  if (var == nullptr) throw std::runtime_error("Mat_VarCreate failed");
  Mat_VarWrite(mat, var, compression);
  Mat_VarFree(var);
}

inline std::string WriteMat(mat_ft version) {
  // One name per process: test programs run in parallel.
  const std::string path = (std::filesystem::temp_directory_path() /
                            ((version == MAT_FT_MAT73 ? "driveid_test73." : "driveid_test5.") +
                             std::to_string(::getpid()) + ".mat"))
                               .string();
  std::remove(path.c_str());
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, version);
  if (mat == nullptr) throw std::runtime_error("Mat_CreateVer failed");
  // time: 1 x 5 row vector; data: 5 x 3 (columns t, position [deg], current);
  // gain: scalar; rec: struct with pos (2 x 5) and time_cont (5 x 1); a cell.
  double time[5] = {0.0, 0.01, 0.02, 0.03, 0.04};
  std::size_t row_dims[2] = {1, 5};
  Put(mat, Mat_VarCreate("time", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, row_dims, time, 0), MAT_COMPRESSION_NONE);
  double data[15] = {0, 0.01, 0.02, 0.03, 0.04, 10, 20, 30, 40, 50, 1, 2, 3, 4, 5};  // column-major
  std::size_t data_dims[2] = {5, 3};
  Put(mat, Mat_VarCreate("data", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, data_dims, data, 0), MAT_COMPRESSION_ZLIB);
  double gain = 2.5;
  std::size_t scalar_dims[2] = {1, 1};
  Put(mat, Mat_VarCreate("gain", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, scalar_dims, &gain, 0), MAT_COMPRESSION_NONE);
  double pos[10] = {1, 100, 2, 200, 3, 300, 4, 400, 5, 500};  // 2 x 5, column-major: row 1 = 1..5
  std::size_t pos_dims[2] = {2, 5};
  double tc[5] = {0.0, 0.1, 0.2, 0.3, 0.4};
  std::size_t tc_dims[2] = {5, 1};
  const char* fields[2] = {"pos", "time_cont"};
  std::size_t struct_dims[2] = {1, 1};
  matvar_t* rec = Mat_VarCreateStruct("rec", 2, struct_dims, fields, 2);
  Mat_VarSetStructFieldByName(rec, "pos", 0, Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, pos_dims, pos, 0));
  Mat_VarSetStructFieldByName(rec, "time_cont", 0,
                              Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, tc_dims, tc, 0));
  Mat_VarWrite(mat, rec, MAT_COMPRESSION_NONE);
  Mat_VarFree(rec);
  double re[5] = {1, 2, 3, 4, 5}, im[5] = {0, 0, 0, 0, 1};
  mat_complex_split_t z = {re, im};
  Put(mat, Mat_VarCreate("z", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, row_dims, &z, MAT_F_COMPLEX));
  Mat_Close(mat);
  std::string bytes = Slurp(path);
  std::remove(path.c_str());
  return bytes;
}

}  // namespace driveid::testing
