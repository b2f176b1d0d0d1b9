#include "common/command_registry.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
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

  using Run = std::function<void(const std::string&)>;
  auto declared = std::make_shared<std::vector<std::pair<CLI::App*, Run>>>();
  for (const auto& entry : top) {
    if (entry.command != nullptr) {
      declared->push_back(entry.command->declare(app));
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
    for (const auto* command : members) declared->push_back(command->declare(*parent));
  }
  for (const auto& command : Commands()) {
    if (command.tool != tool || command.group.empty()) continue;
    bool grouped = false;
    for (const auto& group : Groups()) grouped = grouped || (group.tool == tool && group.name == command.group);
    if (!grouped) throw std::logic_error("command registered in an undeclared group: " + command.group);
  }
  return [declared](const std::string& command_line) {
    for (const auto& [subcommand, run] : *declared) {
      if (*subcommand) run(command_line);
    }
  };
}

namespace {

// Each registration of `tool` with its subcommand's name, found once by
// declaring it on a scratch parent.
const std::vector<std::pair<const CommandRegistration*, std::string>>& NamedCommands(const std::string& tool) {
  static std::mutex mutex;
  static std::map<std::string, std::vector<std::pair<const CommandRegistration*, std::string>>> named;
  const std::lock_guard<std::mutex> lock(mutex);
  auto found = named.find(tool);
  if (found == named.end()) {
    std::vector<std::pair<const CommandRegistration*, std::string>> list;
    for (const auto& command : Commands()) {
      if (command.tool != tool) continue;
      CLI::App scratch;
      list.emplace_back(&command, command.declare(scratch).first->get_name());
    }
    found = named.emplace(tool, std::move(list)).first;
  }
  return found->second;
}

}  // namespace

std::function<void(const std::string&)> SetupCommand(CLI::App& app, const std::string& tool,
                                                     const std::vector<std::string>& words) {
  for (const auto& [command, name] : NamedCommands(tool)) {
    CLI::App* parent = &app;
    if (!command->group.empty()) {
      if (words.size() < 2 || words[0] != command->group || words[1] != name) continue;
      for (const auto& group : Groups()) {
        if (group.tool == tool && group.name == command->group) parent = app.add_subcommand(group.name, group.description);
      }
      parent->require_subcommand(1);
    } else if (words.empty() || words[0] != name) {
      continue;
    }
    auto declared = command->declare(*parent);
    return [declared](const std::string& command_line) {
      if (*declared.first) declared.second(command_line);
    };
  }
  return SetupCommands(app, tool);
}

}  // namespace driveid::cli
