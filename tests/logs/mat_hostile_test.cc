// Hostile MAT v7.3 (HDF5) files (issue 21): cut short at every length —
// refused naming the file, or the same data as the whole file (the v5 sweep
// is in log_input_test.cc); variables whose bytes come from other files.
// Prefixes that hold the superblock are refused before a
// reader process starts; the first ~520 start one each.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <hdf5.h>
#include <matio.h>

#include "core/errors.h"
#include "logs/log_input.h"
#include "support/mat_fixture.h"
#include "support/private_tmpdir.h"

using namespace driveid;

TEST_CASE("MAT v7.3 cut short at every length: refused naming the file, or the same data as the whole file") {
  const std::string bytes = driveid::testing::WriteMat(MAT_FT_MAT73);
  const std::vector<std::string> columns = {"t", "q", "tau|i"};
  LogInputOptions options;
  options.columns = {{"q", "data(:,2)"}, {"i", "data(:,3)"}};
  const auto whole = ReadLogs("whole.mat", bytes, {}, columns, options);
  REQUIRE(whole.size() == 1);
  int refused = 0;
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    try {
      const auto logs = ReadLogs("cut.mat", bytes.substr(0, length), {}, columns, options);
      INFO("prefix of " << length << " of " << bytes.size() << " bytes read");
      REQUIRE(logs.size() == 1);
      CHECK(logs[0].columns == whole[0].columns);
    } catch (const InputError& e) {
      INFO("prefix of " << length << " bytes: " << e.what());
      CHECK(std::string(e.what()).rfind("cut.mat", 0) == 0);
      ++refused;
    }
  }
  CHECK(refused > 0);
}

namespace {

// Creates dataset "stolen" of 1 x 5 doubles in `file` with the creation
// properties `plist` (which say where its data live), marked as MATLAB marks
// a double variable, and closes `plist`.
void AddMatlabDouble(hid_t file, hid_t plist) {
  const hsize_t dims[2] = {1, 5};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t dataset = H5Dcreate2(file, "stolen", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, plist, H5P_DEFAULT);
  REQUIRE(dataset >= 0);
  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, 6);
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(dataset, "MATLAB_class", text, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attribute, text, "double");
  H5Aclose(attribute);
  H5Sclose(scalar);
  H5Tclose(text);
  H5Dclose(dataset);
  H5Pclose(plist);
  H5Sclose(space);
}

// Adds to a v7.3 file (HDF5, written by matio) a double variable `name` of 5
// samples as MATLAB stores one, its data in `how`: "external" raw storage in
// another file, a "virtual" dataset mapped from another HDF5 file, or an
// "external link" to a dataset of another file.
std::string WithForeignData(const std::string& how) {
  const std::string bytes = driveid::testing::WriteMat(MAT_FT_MAT73);
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(::getpid());
  const std::string path = (dir / ("driveid_test73_foreign." + tag + ".mat")).string();
  const std::string secret = (dir / ("driveid_test73_secret." + tag + ".bin")).string();
  const double values[5] = {7, 7, 7, 7, 7};
  {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    std::ofstream other(secret, std::ios::binary);
    other.write(reinterpret_cast<const char*>(values), sizeof values);
  }
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(file >= 0);
  if (how == "external") {
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    REQUIRE(H5Pset_external(plist, secret.c_str(), 0, 5 * sizeof(double)) >= 0);
    AddMatlabDouble(file, plist);
  } else if (how == "virtual") {
    // A virtual dataset mapped from a dataset of another HDF5 file.
    const std::string source = (dir / ("driveid_test73_secret." + tag + ".h5")).string();
    const hsize_t dims[2] = {1, 5};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t other = H5Fcreate(source.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(other >= 0);
    const hid_t stored = H5Dcreate2(other, "values", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(stored, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
    H5Dclose(stored);
    H5Fclose(other);
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    REQUIRE(H5Pset_virtual(plist, space, source.c_str(), "/values", space) >= 0);
    H5Sclose(space);
    AddMatlabDouble(file, plist);
  } else {
    REQUIRE(H5Lcreate_external(secret.c_str(), "/time", file, "stolen", H5P_DEFAULT, H5P_DEFAULT) >= 0);
  }
  H5Fclose(file);
  std::string out = driveid::testing::Slurp(path);
  for (const auto& f : {path, secret, (dir / ("driveid_test73_secret." + tag + ".h5")).string()}) std::remove(f.c_str());
  return out;
}

}  // namespace

TEST_CASE("MAT v7.3 whose variable reads another file's bytes (external storage, virtual dataset, external link) is refused naming it") {
  LogInputOptions options;
  options.columns = {{"q", "data(:,2)"}, {"i", "data(:,3)"}};
  for (const std::string how : {"external", "external link", "virtual"}) {
    INFO(how);
    const std::string bytes = WithForeignData(how);
    try {
      ReadLogs("foreign.mat", bytes, {}, {"t", "q", "tau|i"}, options);
      FAIL("read");
    } catch (const InputError& e) {
      const std::string message = e.what();
      CHECK(message.rfind("foreign.mat: ", 0) == 0);
      CHECK(message.find("'stolen'") != std::string::npos);
      CHECK(message.find(how == "external" ? "external files" : how == "virtual" ? "virtual dataset" : "external link") !=
            std::string::npos);
    }
  }
}

namespace {

// A MAT v5 file with `extra` scalars besides t, q, tau (5 samples).
std::string WithManyVariables(std::size_t extra) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("driveid_test5_many." + std::to_string(::getpid()) + ".mat")).string();
  std::remove(path.c_str());
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
  REQUIRE(mat != nullptr);
  std::size_t scalar_dims[2] = {1, 1}, column_dims[2] = {5, 1};
  for (std::size_t k = 0; k < extra; ++k) {
    double value = static_cast<double>(k);
    const std::string name = "p" + std::to_string(k);
    driveid::testing::Put(mat, Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, scalar_dims, &value, 0));
  }
  double t[5] = {0, 0.1, 0.2, 0.3, 0.4}, q[5] = {0, 1, 4, 9, 16}, tau[5] = {1, 1, 1, 1, 1};
  driveid::testing::Put(mat, Mat_VarCreate("t", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, column_dims, t, 0));
  driveid::testing::Put(mat, Mat_VarCreate("q", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, column_dims, q, 0));
  driveid::testing::Put(mat, Mat_VarCreate("tau", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, column_dims, tau, 0));
  Mat_Close(mat);
  std::string out = driveid::testing::Slurp(path);
  std::remove(path.c_str());
  return out;
}

// The same, written byte by byte (matio's writer is quadratic in the number
// of variables: 100 000 took 13 s): little-endian v5, each scalar a miMATRIX
// element of flags, dimensions 1 x 1, name and one miDOUBLE.
std::string ManyScalarsV5(std::size_t count) {
  std::string out(116, ' ');
  out.replace(0, 19, "MATLAB 5.0 MAT-file");
  out.append(8, '\0');  // subsystem data offset
  const auto u16 = [&](std::uint16_t v) { out.append(reinterpret_cast<const char*>(&v), 2); };
  const auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u16(0x0100);
  out += "IM";
  for (std::size_t k = 0; k < count; ++k) {
    const std::string name = "p" + std::to_string(k);
    const std::uint32_t padded = static_cast<std::uint32_t>((name.size() + 7) / 8 * 8);
    u32(14);  // miMATRIX
    u32(16 + 16 + 8 + padded + 16);
    u32(6), u32(8), u32(6), u32(0);  // array flags: miUINT32, 8 bytes, class double
    u32(5), u32(8), u32(1), u32(1);  // dimensions: miINT32, 1 x 1
    u32(1), u32(static_cast<std::uint32_t>(name.size()));  // name: miINT8
    out += name;
    out.append(padded - name.size(), '\0');
    u32(9), u32(8);  // miDOUBLE, 8 bytes
    const double value = static_cast<double>(k);
    out.append(reinterpret_cast<const char*>(&value), 8);
  }
  return out;
}

}  // namespace

TEST_CASE("MAT with many variables: read in one pass (20 000 scalars), refused beyond the limit, never truncated") {
  // Reading by name rescanned the file per variable: 700 variables took 4 s
  // and 1000 were refused by the reader's 5 s limit.
  const auto logs = ReadLogs("many.mat", WithManyVariables(20000), {}, {"t", "q", "tau"}, {});
  REQUIRE(logs.size() == 1);
  CHECK(logs[0].columns[1] == std::vector<double>{0, 1, 4, 9, 16});
  try {
    ReadLogs("too_many.mat", ManyScalarsV5(100001), {}, {"t", "q", "tau"}, {});
    FAIL("read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "too_many.mat: more than 100000 variables: a log file holds at most 100000");
  }
}

TEST_CASE("a MAT read names no file: nothing in the temporary folder is created, swept or left behind") {
  // Files that look like the copies older versions made, of a process that
  // has exited and of this one: a user's, never the tool's to remove.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  REQUIRE(child > 0);
  ::waitpid(child, nullptr, 0);
  const driveid::testing::PrivateTmpdir private_tmpdir;
  const auto dir = std::filesystem::temp_directory_path();
  REQUIRE(dir == std::filesystem::path(private_tmpdir.path()));
  const auto foreign = dir / ("driveid-mat." + std::to_string(child) + ".mine");
  const auto live = dir / ("driveid-mat." + std::to_string(::getpid()) + ".Ef34Gh");
  std::ofstream(foreign) << "mine";
  std::ofstream(live) << "live";
  const auto listing = [&] {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) names.insert(entry.path().filename().string());
    return names;
  };
  const auto before = listing();
  LogInputOptions options;
  options.columns = {{"t", "time"}, {"q", "data(:,2)"}, {"tau", "data(:,3)"}};
  for (const int version : {MAT_FT_MAT5, MAT_FT_MAT73}) {
    const auto logs = ReadLogs("m.mat", driveid::testing::WriteMat(static_cast<mat_ft>(version)), {}, {"t", "q", "tau|i"}, options);
    CHECK(logs.size() == 1);
  }
  CHECK(listing() == before);
  CHECK(std::filesystem::exists(foreign));
  CHECK(std::filesystem::exists(live));
  std::filesystem::remove(foreign);
  std::filesystem::remove(live);
}
