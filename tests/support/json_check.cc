// json_check FILE: exit 0 if FILE holds exactly one valid JSON document
// (whitespace around it allowed), else print the parser's message and exit 1.
// Used by the CLI tests to check every subcommand's --json output.
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: json_check FILE\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  try {
    const auto document = nlohmann::json::parse(text.str());
    if (!document.is_object()) {
      std::cerr << argv[1] << ": not a JSON object\n";
      return 1;
    }
  } catch (const nlohmann::json::parse_error& e) {
    std::cerr << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
