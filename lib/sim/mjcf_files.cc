#include "sim/mjcf_files.h"

#include <cctype>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/csv_log.h"

namespace driveid {
namespace {

constexpr int kMaxDepth = 8;
constexpr std::size_t kMaxFiles = 64;

struct Reference {
  std::string element, attribute, value;  ///< element: the tag the attribute stands in
};

// The name of the element whose start tag holds position `at`.
std::string ElementAt(const std::string& text, std::size_t at) {
  const std::size_t open = text.rfind('<', at);
  if (open == std::string::npos) return "";
  std::size_t end = open + 1;
  while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) && text[end] != '>' &&
         text[end] != '/') {
    ++end;
  }
  return text.substr(open + 1, end - open - 1);
}

// Values of the attributes `file`, a cube texture's six faces' `fileright`
// .. `fileback`, `meshdir`, `texturedir`, `assetdir` (a whole attribute
// name: preceded by a blank), single or double quoted.
std::vector<Reference> FileReferences(const std::string& text) {
  std::vector<Reference> out;
  for (const char* name : {"file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback", "meshdir",
                           "texturedir", "assetdir"}) {
    const std::string key = name;
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
      if (at == 0 || !std::isspace(static_cast<unsigned char>(text[at - 1]))) continue;
      std::size_t i = at + key.size();
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i >= text.size() || text[i] != '=') continue;
      ++i;
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i >= text.size() || (text[i] != '"' && text[i] != '\'')) continue;
      const std::size_t end = text.find(text[i], i + 1);
      if (end == std::string::npos) continue;  // MuJoCo refuses the XML itself
      out.push_back({ElementAt(text, at), key, text.substr(i + 1, end - i - 1)});
    }
  }
  return out;
}

// Why `value` may not be read (empty: it may).
std::string Problem(const std::string& value, const std::filesystem::path& folder, bool directory) {
  if (value.find('&') != std::string::npos) return "a character reference or entity";
  const std::filesystem::path p(value);
  if (p.is_absolute()) return "an absolute path";
  for (const auto& part : p) {
    if (part == "..") return "a '..'";
  }
  std::error_code error;
  const auto resolved = std::filesystem::weakly_canonical(folder / p, error);
  const auto root = std::filesystem::weakly_canonical(folder, error);
  if (error) return "a path that cannot be resolved";
  const std::string r = resolved.string(), f = root.string();
  if (r.compare(0, f.size(), f) != 0 || (r.size() > f.size() && r[f.size()] != '/')) {
    return "a link that leads outside the model's folder";
  }
  if (!directory && std::filesystem::exists(resolved, error) && !std::filesystem::is_regular_file(resolved, error)) {
    return "not a regular file";
  }
  return "";
}

void Check(const std::filesystem::path& file, const std::filesystem::path& folder, int depth, std::size_t& files) {
  if (++files > kMaxFiles) throw InputError(fmt::format("{}: more than {} included files", file.string(), kMaxFiles));
  if (depth > kMaxDepth) throw InputError(fmt::format("{}: includes nested more than {} deep", file.string(), kMaxDepth));
  ReadLimits limits;
  limits.max_bytes = std::size_t{64} << 20;
  limits.max_line_bytes = 0;
  limits.max_bytes_hint = "an MJCF may be at most 64 MiB";
  const std::string text = ReadFileToString(file.string(), limits);
  for (const Reference& r : FileReferences(text)) {
    const bool directory = r.attribute.size() > 3 && r.attribute.compare(r.attribute.size() - 3, 3, "dir") == 0;
    const std::string why = Problem(r.value, folder, directory);
    if (!why.empty()) {
      throw InputError(fmt::format("{}: {}=\"{}\": {}; MuJoCo may read only files in the model's folder {}",
                                   file.string(), r.attribute, r.value.substr(0, 200), why, folder.string()));
    }
    // An included model is checked too (MuJoCo reads it relative to the top model's folder).
    if (r.element == "include") {
      const auto included = folder / r.value;
      std::error_code error;
      if (std::filesystem::is_regular_file(included, error)) Check(included, folder, depth + 1, files);
    }
  }
}

}  // namespace

void CheckMjcfFiles(const std::string& model_path) {
  const std::filesystem::path path(model_path);
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::size_t files = 0;
  Check(path, folder, 0, files);
}

}  // namespace driveid
