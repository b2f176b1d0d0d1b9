#include "logs/table_source.h"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

std::optional<std::size_t> TableSource::Find(const std::string& reference) const {
  const auto names = column_names();
  if (reference.size() >= 2 && reference[0] == '#') {
    std::size_t k = 0;
    const auto result = std::from_chars(reference.data() + 1, reference.data() + reference.size(), k);
    if (result.ec == std::errc() && result.ptr == reference.data() + reference.size() && k >= 1 && k <= names.size()) {
      return k - 1;
    }
    return std::nullopt;
  }
  std::optional<std::size_t> found;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] != reference) continue;
    if (found) {
      throw InputError(fmt::format("{}: column '{}' occurs at #{} and #{}: name it by position", path(), reference,
                                   *found + 1, i + 1));
    }
    found = i;
  }
  return found;
}

std::string ChooseName(const std::vector<std::string>& found, const std::string& wanted, const char* what,
                       const char* option, const std::string& path) {
  if (!wanted.empty()) {
    if (std::find(found.begin(), found.end(), wanted) != found.end()) return wanted;
    throw OptionError(fmt::format("‹{}› {}: {} has no such {} (found: {})", option, wanted, path, what,
                                  found.empty() ? std::string("none") : fmt::format("{}", fmt::join(found, ", "))));
  }
  if (found.size() == 1) return found.front();
  if (found.empty()) throw InputError(fmt::format("{}: no {} (inspect lists what it holds)", path, what));
  throw OptionError(fmt::format("{}: {} {}s ({}): give ‹{}›", path, found.size(), what, fmt::join(found, ", "), option));
}

namespace {

class MemorySource : public TableSource {
 public:
  explicit MemorySource(MemorySourceParts parts) : p_(std::move(parts)) {}
  std::string path() const override { return p_.path; }
  std::string segment() const override { return p_.segment; }
  std::string format() const override { return p_.format; }
  std::string units() const override { return p_.units; }
  std::string mechanism() const override { return p_.mechanism; }
  std::vector<std::string> column_names() const override { return p_.names; }
  std::vector<std::size_t> column_lengths() const override {
    return std::vector<std::size_t>(p_.names.size(), p_.columns.empty() ? 0 : p_.columns.front().size());
  }
  std::vector<SourceVariable> variables() const override { return p_.variables; }
  std::vector<std::string> notes() const override { return p_.notes; }
  std::string DefaultReference(const std::string& logical) const override {
    const auto found = p_.defaults.find(logical);
    return found == p_.defaults.end() ? std::string() : found->second;
  }
  TableData Read(const std::vector<std::size_t>& columns) const override {
    TableData out;
    for (auto c : columns) out.columns.push_back(p_.columns.at(c));
    return out;
  }

 private:
  MemorySourceParts p_;
};

}  // namespace

std::unique_ptr<TableSource> MakeMemorySource(MemorySourceParts parts) {
  return std::make_unique<MemorySource>(std::move(parts));
}

std::map<std::string, std::string> SysIdDefaults() {
  return {{"q", "position"}, {"qd", "velocity"}, {"tau", "voltage"}};
}

}  // namespace driveid
