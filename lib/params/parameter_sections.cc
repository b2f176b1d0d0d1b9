#include "params/parameter_sections.h"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "params/parameter_numbers.h"

namespace driveid {

namespace section_io {

std::string Where(const std::string& path, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return path;
  return fmt::format("{}:{}:{}", path, mark.line + 1, mark.column + 1);
}

double ParseNumber(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsScalar()) throw InputError(fmt::format("{}: {}: expected a number", Where(path, node), name));
  const std::string& text = node.Scalar();
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (begin != end && *begin == '+') ++begin;
  double value = 0.0;
  const auto result = std::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value)) {
    throw InputError(fmt::format("{}: {}: not a finite number: \"{}\"", Where(path, node), name,
                                 text.substr(0, 40)));
  }
  // Products and quotients of a few parameters (k_eq, omega_n, ...) must stay
  // finite: values are 0 or within 1e-100 <= |v| <= 1e100 (docs/formats.md).
  if (value != 0.0 && !(std::abs(value) >= kSmallestParameterMagnitude && std::abs(value) <= kLargestParameterMagnitude)) {
    throw InputError(fmt::format("{}: {} = {}: outside the range of parameter values (0 or 1e-100 <= |value| <= 1e100)",
                                 Where(path, node), name, text.substr(0, 40)));
  }
  return value;
}

double ParseStandardError(const std::string& path, const std::string& name, const YAML::Node& node) {
  const double value = ParseNumber(path, name, node);
  if (value < 0.0) throw InputError(fmt::format("{}: {} = {}: a standard error is >= 0", Where(path, node), name, value));
  return value;
}

// Refuses non-mappings, duplicate and non-scalar keys.
void CheckMapping(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsMap()) throw InputError(fmt::format("{}: {}: expected a mapping of keys", Where(path, node), name));
  std::set<std::string> seen;
  for (const auto& item : node) {
    if (!item.first.IsScalar()) throw InputError(fmt::format("{}: {}: keys must be names", Where(path, item.first), name));
    if (!seen.insert(item.first.Scalar()).second) {
      throw InputError(fmt::format("{}: {}.{}: key appears twice", Where(path, item.first), name, item.first.Scalar()));
    }
  }
}

std::string Number(double value) { return fmt::format("{}", value); }

std::string YamlName(const std::string& name) {
  bool plain = !name.empty();
  for (char c : name) plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  if (plain) return name;
  std::string quoted = "\"";
  for (char c : name) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

std::string ParseText(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsScalar()) throw InputError(fmt::format("{}: {}: expected text", Where(path, node), name));
  return node.Scalar();
}

// A value as the reader will accept it (ParseNumber): finite, 0 or within
// 1e-100 <= |v| <= 1e100; else nothing is written.
double Writable(const std::string& name, double value) {
  if (!std::isfinite(value) ||
      (value != 0.0 && !(std::abs(value) >= kSmallestParameterMagnitude && std::abs(value) <= kLargestParameterMagnitude))) {
    throw OutputError(fmt::format("{} = {}: outside what a parameter file holds (finite, 0 or 1e-100 <= |value| <= "
                                  "1e100); nothing written (rescale the data)",
                                  name, value));
  }
  return value;
}

// CheckMapping, and every key one of `known`.
void CheckKeys(const std::string& path, const std::string& name, const YAML::Node& node,
               const std::vector<std::string>& known) {
  CheckMapping(path, name, node);
  for (const auto& item : node) {
    if (std::find(known.begin(), known.end(), item.first.Scalar()) == known.end()) {
      throw InputError(fmt::format("{}: {}.{}: unknown key (known: {})", Where(path, item.first), name,
                                   item.first.Scalar().substr(0, 64), fmt::join(known, ", ")));
    }
  }
}

namespace {

// Length of the valid UTF-8 sequence starting at text[i], or 0.
std::size_t Utf8Length(const std::string& text, std::size_t i) {
  const unsigned char lead = static_cast<unsigned char>(text[i]);
  std::size_t length = 0;
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF) length = 3;
  else if (lead >= 0xF0 && lead <= 0xF4) length = 4;
  else return 0;
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 0;
  }
  return length;
}

}  // namespace

// A YAML double-quoted string: control characters and bytes that are not
// UTF-8 (a file name may hold any bytes) are escaped as \xNN.
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7F) {
      out += fmt::format("\\x{:02x}", u);
    } else if (u >= 0x80) {
      const std::size_t length = Utf8Length(text, i);
      if (length == 0) {
        out += fmt::format("\\x{:02x}", u);
      } else {
        out.append(text, i, length);
        i += length - 1;
      }
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// Text for a comment: as is when it is printable ASCII, else quoted and
// escaped — a unit read from a log must not end the comment and start a key.
std::string Comment(const std::string& text) {
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7F; });
  return plain ? text : Quoted(text);
}

std::string Short(double value) { return fmt::format("{:.6g}", value); }

}  // namespace section_io

// The factories of the sections lib/CMakeLists.txt lists in
// DRIVEID_PARAMETER_SECTIONS (each defined by DRIVEID_PARAMETER_SECTION in
// its file), in its order: the order they are written.
#define DRIVEID_REGISTERED_PARAMETER_SECTION(name) SectionHandler MakeParameterSection_##name();
#include "params/registered_parameter_sections.inc"
#undef DRIVEID_REGISTERED_PARAMETER_SECTION

namespace {

std::vector<SectionHandler>& Sections() {
  static std::vector<SectionHandler> sections = [] {
    std::vector<SectionHandler> made;
#define DRIVEID_REGISTERED_PARAMETER_SECTION(name) made.push_back(MakeParameterSection_##name());
#include "params/registered_parameter_sections.inc"
#undef DRIVEID_REGISTERED_PARAMETER_SECTION
    return made;
  }();
  return sections;
}

}  // namespace

void RegisterParameterSection(SectionHandler handler) {
  for (const auto& section : Sections()) {
    if (section.name == handler.name) {
      throw std::logic_error("RegisterParameterSection: section '" + handler.name + "' exists already");
    }
  }
  Sections().push_back(std::move(handler));
}

const std::vector<SectionHandler>& ParameterSections() { return Sections(); }

}  // namespace driveid
