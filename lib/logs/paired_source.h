// Two sources side by side (`--join`): the log's source first, the joined
// file's after it, positions counting on. What both kinds of join share;
// they differ in how rows meet (row by row in paired_source.cc, by time in
// time_join.cc).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "logs/table_source.h"

namespace driveid {

class PairedSource : public TableSource {
 public:
  PairedSource(std::unique_ptr<TableSource> a, std::unique_ptr<TableSource> b) : a_(std::move(a)), b_(std::move(b)) {}
  std::string path() const override { return a_->path(); }
  std::string segment() const override { return a_->segment(); }
  std::string format() const override { return a_->format(); }
  int header_line() const override { return a_->header_line(); }
  std::vector<std::string> column_names() const override {
    auto names = a_->column_names();
    for (const auto& n : b_->column_names()) names.push_back(n);
    return names;
  }
  std::optional<double> scalar(const std::string& name) const override {
    auto v = a_->scalar(name);
    return v ? v : b_->scalar(name);
  }
  std::vector<SourceVariable> variables() const override {
    auto variables = a_->variables();
    for (auto& v : b_->variables()) variables.push_back(std::move(v));
    return variables;
  }
  std::vector<std::string> comments() const override { return a_->comments(); }

 protected:
  /// Splits requested columns into those of a and those of b (b's counted from its own first).
  void Split(const std::vector<std::size_t>& columns, std::vector<std::size_t>& in_a, std::vector<std::size_t>& in_b) const {
    const std::size_t split = a_->column_names().size();
    for (auto c : columns) (c < split ? in_a : in_b).push_back(c < split ? c : c - split);
  }
  bool InA(std::size_t column) const { return column < a_->column_names().size(); }

  std::unique_ptr<TableSource> a_, b_;
};

/// Two sources side by side, row by row (`--join`): positions count on
/// across them. Throws InputError when their row counts differ.
std::unique_ptr<TableSource> JoinSources(std::unique_ptr<TableSource> first, std::unique_ptr<TableSource> second);

}  // namespace driveid
