#include "logs/formats/mat_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <unistd.h>

#include <fmt/format.h>
#include <matio.h>

#include "core/errors.h"
#include "logs/formats/hdf5_storage_check.h"
#include "logs/formats/mat_structure_check.h"

namespace driveid {
namespace {

// matio logs through a global function: keep its last message for ours
// (the library prints nothing).
std::mutex log_mutex;
std::string last_matio_message;

void CaptureMatioLog(int, char* message) {
  if (message != nullptr) last_matio_message = message;
}

constexpr std::size_t kMaxVariables = 100000;  // top-level variables of one file

template <typename T>
void Convert(const void* data, std::size_t n, std::vector<double>& out) {
  const T* p = static_cast<const T*>(data);
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(p[i]);
}

bool ConvertNumeric(const matvar_t* v, std::size_t n, std::vector<double>& out) {
  if (v->data == nullptr) return false;
  switch (v->class_type) {
    case MAT_C_DOUBLE: Convert<double>(v->data, n, out); return true;
    case MAT_C_SINGLE: Convert<float>(v->data, n, out); return true;
    case MAT_C_INT8: Convert<std::int8_t>(v->data, n, out); return true;
    case MAT_C_UINT8: Convert<std::uint8_t>(v->data, n, out); return true;
    case MAT_C_INT16: Convert<std::int16_t>(v->data, n, out); return true;
    case MAT_C_UINT16: Convert<std::uint16_t>(v->data, n, out); return true;
    case MAT_C_INT32: Convert<std::int32_t>(v->data, n, out); return true;
    case MAT_C_UINT32: Convert<std::uint32_t>(v->data, n, out); return true;
    case MAT_C_INT64: Convert<std::int64_t>(v->data, n, out); return true;
    case MAT_C_UINT64: Convert<std::uint64_t>(v->data, n, out); return true;
    default: return false;
  }
}

// The bytes a variable's header claims (dimensions × element size), summed
// over struct fields and cells; overflow and absurd ranks count as infinite.
double ClaimedBytes(matvar_t* var, int depth) {
  if (var == nullptr) return 0.0;
  if (depth > 16 || var->rank < 0 || var->rank > 32 || (var->rank > 0 && var->dims == nullptr)) return HUGE_VAL;
  double elements = 1.0;
  for (int k = 0; k < var->rank; ++k) elements *= static_cast<double>(var->dims[k]);
  if (var->class_type == MAT_C_STRUCT) {
    const unsigned fields = Mat_VarGetNumberOfFields(var);
    double total = 64.0 * elements * fields;
    if (elements > 1e6 || var->data == nullptr) return total;
    for (std::size_t i = 0; i < static_cast<std::size_t>(elements) && total < HUGE_VAL; ++i) {
      for (unsigned f = 0; f < fields; ++f) total += ClaimedBytes(Mat_VarGetStructFieldByIndex(var, f, i), depth + 1);
    }
    return total;
  }
  if (var->class_type == MAT_C_CELL) {
    double total = 64.0 * elements;
    if (elements > 1e6 || var->data == nullptr) return total;
    for (std::size_t i = 0; i < static_cast<std::size_t>(elements) && total < HUGE_VAL; ++i) {
      total += ClaimedBytes(Mat_VarGetCell(var, static_cast<int>(i)), depth + 1);
    }
    return total;
  }
  const double size = static_cast<double>(std::max<std::size_t>(Mat_SizeOfClass(var->class_type), 1));
  return elements * size * (var->isComplex ? 2.0 : 1.0);
}

const char* ClassName(matio_classes c) {
  switch (c) {
    case MAT_C_CELL: return "cell array";
    case MAT_C_STRUCT: return "struct array";
    case MAT_C_OBJECT: return "object";
    case MAT_C_CHAR: return "text";
    case MAT_C_SPARSE: return "sparse matrix";
    case MAT_C_FUNCTION: return "function handle";
    case MAT_C_OPAQUE: return "opaque object";
    case MAT_C_EMPTY: return "empty array";
    default: return "numeric";
  }
}

class MatReader {
 public:
  explicit MatReader(std::string path) : path_(std::move(path)) {}
  MatContents Read(const std::string& file) {
    LoadHere(file);
    return std::move(contents_);
  }

 private:
  void LoadHere(const std::string& file) {
    std::lock_guard<std::mutex> lock(log_mutex);
    Mat_LogInitFunc("driveid", CaptureMatioLog);
    last_matio_message.clear();
    mat_t* mat = Mat_Open(file.c_str(), MAT_ACC_RDONLY);
    if (mat == nullptr) {
      throw InputError(fmt::format("{}: not a readable MAT file{}", path_,
                                   last_matio_message.empty() ? "" : ": " + last_matio_message));
    }
    // Sizes claimed in the headers are checked before anything is read: a
    // variable cannot hold more bytes than the file could inflate to (zlib
    // expands at most ~1032-fold), so a hostile header never makes matio
    // allocate gigabytes.
    std::error_code error;
    const std::uintmax_t file_size = std::filesystem::file_size(file, error);
    const double byte_budget = 1100.0 * static_cast<double>(error ? 0 : file_size) + 4096.0;
    // First pass: headers only. Second pass in the same order: each
    // variable read in turn (Mat_VarRead by name rescans the file from the
    // start: quadratic in the number of variables), the refused ones skipped
    // by their headers.
    std::vector<bool> wanted;
    std::size_t variables = 0;
    while (matvar_t* info = Mat_VarReadNextInfo(mat)) {
      bool ok = false;
      if (info->name != nullptr) {
        if (++variables > kMaxVariables) {
          Mat_VarFree(info);
          Mat_Close(mat);
          throw InputError(fmt::format("{}: more than {} variables: a log file holds at most {}", path_, kMaxVariables,
                                       kMaxVariables));
        }
        const double claimed = ClaimedBytes(info, 0);
        ok = claimed <= byte_budget && claimed <= 8.0 * static_cast<double>(kMaxMatElements);
        if (!ok) {
          contents_.notes.push_back(fmt::format("{}: skipped (its header claims {:.3g} bytes in a file of {} bytes)", info->name,
                                       claimed, file_size));
        }
      }
      wanted.push_back(ok);
      Mat_VarFree(info);
    }
    std::size_t elements = 0;
    try {
      if (Mat_Rewind(mat) != 0) throw InputError(fmt::format("{}: not a readable MAT file (cannot rewind)", path_));
      for (std::size_t index = 0; index < wanted.size(); ++index) {
        if (!wanted[index]) {
          if (matvar_t* info = Mat_VarReadNextInfo(mat)) Mat_VarFree(info);
          continue;
        }
        matvar_t* var = Mat_VarReadNext(mat);
        if (var == nullptr) {
          contents_.notes.push_back(fmt::format("variable {}: skipped (matio cannot read it{})", index + 1,
                                       last_matio_message.empty() ? "" : ": " + last_matio_message));
          continue;
        }
        const std::string name = var->name != nullptr ? var->name : "";
        try {
          Add(var, name, 0, elements);
        } catch (...) {
          Mat_VarFree(var);
          throw;
        }
        Mat_VarFree(var);
      }
    } catch (...) {
      Mat_Close(mat);
      throw;
    }
    Mat_Close(mat);
  }

  void Add(matvar_t* var, const std::string& name, int depth, std::size_t& elements) {
    if (var->rank != 2 || var->dims == nullptr) {
      contents_.notes.push_back(fmt::format("{}: skipped ({}-dimensional)", name, var->rank));
      return;
    }
    const std::size_t rows = var->dims[0], cols = var->dims[1];
    if (var->class_type == MAT_C_STRUCT) {
      if (rows * cols != 1 || depth > 16) {
        contents_.notes.push_back(fmt::format("{}: skipped (struct array {} x {}; give one struct)", name, rows, cols));
        return;
      }
      const unsigned count = Mat_VarGetNumberOfFields(var);
      char* const* fields = Mat_VarGetStructFieldnames(var);
      for (unsigned f = 0; f < count && fields != nullptr; ++f) {
        matvar_t* field = Mat_VarGetStructFieldByIndex(var, f, 0);
        if (field != nullptr && fields[f] != nullptr) Add(field, name + "." + fields[f], depth + 1, elements);
      }
      return;
    }
    if (var->isComplex) {
      contents_.notes.push_back(fmt::format("{}: skipped (complex numbers)", name));
      return;
    }
    MatVariable v{name, rows, cols, {}};
    if (rows == 0 || cols == 0 || rows > kMaxMatElements / std::max<std::size_t>(cols, 1) ||
        elements + rows * cols > kMaxMatElements) {
      contents_.notes.push_back(fmt::format("{}: skipped ({} x {} {})", name, rows, cols,
                                   rows == 0 || cols == 0 ? "empty" : "too large"));
      return;
    }
    if (!ConvertNumeric(var, rows * cols, v.data)) {
      contents_.notes.push_back(fmt::format("{}: skipped ({})", name, ClassName(var->class_type)));
      return;
    }
    elements += rows * cols;
    contents_.variables.push_back(std::move(v));
  }

  std::string path_;
  MatContents contents_;
};

}  // namespace

MatContents ReadMatFile(const std::string& path, const std::string& file, const std::string& bytes) {
  CheckMatV5Elements(path, bytes);
  CheckHdf5Storage(path, file);
  return MatReader(path).Read(file);
}

namespace {

// The name of a v7.3 copy while it exists, for RemoveMatReaderCopyNow().
char copy_name[4096 + 16] = "";
char copy_folder[4096] = "";

bool IsHdf5(const std::string& bytes) {
  static const std::string signature("\x89HDF\r\n\x1a\n", 8);
  return bytes.size() >= 520 && bytes.compare(512, 8, signature) == 0;
}

// Reads `bytes` (of `path`) as a named file: HDF5 resolves the name it is
// given with realpath(), which fails for /proc/self/fd of an unnamed file,
// so a v7.3 file gets a name for the read, in a private folder of the
// temporary directory, removed when the read ends.
MatContents ReadNamedCopy(const std::string& path, const std::string& bytes) {
  std::error_code error;
  const std::string pattern = (std::filesystem::temp_directory_path(error) / "driveid-mat.XXXXXX").string();
  if (error || pattern.size() + 16 >= sizeof copy_folder) throw InputError(path + ": no temporary folder for the MAT reader");
  std::snprintf(copy_folder, sizeof copy_folder, "%s", pattern.c_str());
  if (::mkdtemp(copy_folder) == nullptr) {
    copy_folder[0] = '\0';
    throw InputError(path + ": cannot create a temporary copy for the MAT reader");
  }
  std::snprintf(copy_name, sizeof copy_name, "%s/copy.mat", copy_folder);
  try {
    {
      std::ofstream out(copy_name, std::ios::binary);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      if (!out.flush()) throw InputError(path + ": cannot write a temporary copy for the MAT reader");
    }
    MatContents contents = ReadMatFile(path, copy_name, bytes);
    RemoveMatReaderCopyNow();
    return contents;
  } catch (...) {
    RemoveMatReaderCopyNow();
    throw;
  }
}

}  // namespace

void RemoveMatReaderCopyNow() noexcept {
  if (copy_name[0] != '\0') ::unlink(copy_name);
  if (copy_folder[0] != '\0') ::rmdir(copy_folder);
  copy_name[0] = copy_folder[0] = '\0';
}

std::string MatReaderReply(const std::string& path, const std::string& file) {
  try {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw InputError(path + ": cannot read the MAT file");
    if (IsHdf5(bytes) && file.rfind("/proc/self/fd/", 0) == 0) return SerialiseMatReply(ReadNamedCopy(path, bytes));
    return SerialiseMatReply(ReadMatFile(path, file, bytes));
  } catch (const std::exception& e) {
    return SerialiseMatError(e.what());
  } catch (...) {
    return SerialiseMatError(path + ": the MAT reader failed");
  }
}

bool WriteMatReaderReply(int fd, const std::string& reply) {
  std::size_t written = 0;
  while (written < reply.size()) {
    const ssize_t n = ::write(fd, reply.data() + written, reply.size() - written);
    if (n <= 0) return false;
    written += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace driveid
