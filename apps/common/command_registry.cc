#include "common/command_registry.h"

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

namespace driveid::cli {
namespace {

struct Group {
  std::string tool, name, description;
  int order = 0;
};

// Function-local statics: safe to use from other files' static initialisers.
std::vector<CommandRegistration>& Commands() {
  static std::vector<CommandRegistration> commands;
  return commands;
}

std::vector<Group>& Groups() {
  static std::vector<Group> groups;
  return groups;
}

}  // namespace

bool RegisterCommand(CommandRegistration registration) {
  Commands().push_back(std::move(registration));
  return true;
}

bool RegisterGroup(const std::string& tool, const std::string& group, int order, const std::string& description) {
  Groups().push_back({tool, group, description, order});
  return true;
}

std::function<void(const std::string&)> SetupCommands(CLI::App& app, const std::string& tool) {
  // Top-level entries (commands and groups) by order, then each group's members.
  struct Entry {
    int order;
    const CommandRegistration* command;
    const Group* group;
  };
  std::vector<Entry> top;
  for (const auto& command : Commands()) {
    if (command.tool == tool && command.group.empty()) top.push_back({command.order, &command, nullptr});
  }
  for (const auto& group : Groups()) {
    if (group.tool == tool) top.push_back({group.order, nullptr, &group});
  }
  std::stable_sort(top.begin(), top.end(), [](const Entry& a, const Entry& b) { return a.order < b.order; });

  auto declared = std::make_shared<std::vector<std::pair<CLI::App*, const CommandRegistration*>>>();
  for (const auto& entry : top) {
    if (entry.command != nullptr) {
      declared->emplace_back(entry.command->setup(app), entry.command);
      continue;
    }
    CLI::App* parent = app.add_subcommand(entry.group->name, entry.group->description);
    parent->require_subcommand(1);
    std::vector<const CommandRegistration*> members;
    for (const auto& command : Commands()) {
      if (command.tool == tool && command.group == entry.group->name) members.push_back(&command);
    }
    std::stable_sort(members.begin(), members.end(),
                     [](const CommandRegistration* a, const CommandRegistration* b) { return a->order < b->order; });
    for (const auto* command : members) declared->emplace_back(command->setup(*parent), command);
  }
  for (const auto& command : Commands()) {
    if (command.tool != tool || command.group.empty()) continue;
    bool grouped = false;
    for (const auto& group : Groups()) grouped = grouped || (group.tool == tool && group.name == command.group);
    if (!grouped) throw std::logic_error("command registered in an undeclared group: " + command.group);
  }
  return [declared](const std::string& command_line) {
    for (const auto& [subcommand, registration] : *declared) {
      if (*subcommand) registration->run(command_line);
    }
  };
}

}  // namespace driveid::cli
