// The README is the front door: it stays short, its synopsis names every subcommand that
// `accelbench --help` lists, and every file it links to exists.

#include "cli_run.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace {

using test_files::read;

std::string readme() { return read(ACCELBENCH_SOURCE_DIR "/README.md"); }

/// The subcommands `accelbench --help` lists: the indented names under "Subcommands:".
std::set<std::string> subcommands_of_help() {
  const cli_run::CliRun help = cli_run::run(std::string(ACCELBENCH_CLI) + " --help");
  EXPECT_EQ(help.status, 0) << help.output;
  std::set<std::string> names;
  std::istringstream lines(help.output);
  std::string line;
  bool in_list = false;
  const std::regex entry(R"(^  ([a-z][a-z_-]*)\s)");
  while (std::getline(lines, line)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_list = true;
      continue;
    }
    std::smatch m;
    if (in_list && std::regex_search(line, m, entry)) names.insert(m[1]);
  }
  return names;
}

TEST(Readme, IsAFrontDoorOfAtMost10KB) {
  const std::string text = readme();
  ASSERT_FALSE(text.empty()) << "README.md not found in " << ACCELBENCH_SOURCE_DIR;
  EXPECT_LE(text.size(), 10u * 1024u) << "README.md is " << text.size()
                                      << " bytes; measurements and details belong in docs/";
}

TEST(Readme, SynopsisNamesEverySubcommandOfHelp) {
  const std::set<std::string> names = subcommands_of_help();
  ASSERT_GE(names.size(), 5u) << "could not read the subcommands of accelbench --help";
  const std::string text = readme();
  for (const std::string& name : names)
    EXPECT_NE(text.find("\naccelbench " + name + " "), std::string::npos)
        << "the README's synopsis has no line 'accelbench " << name << " ...'";
}

TEST(Readme, SynopsisNamesNoSubcommandThatHelpLacks) {
  const std::set<std::string> names = subcommands_of_help();
  const std::string text = readme();
  const std::regex synopsis_line(R"(\naccelbench ([a-z][a-z_-]*) )");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), synopsis_line); it != std::sregex_iterator(); ++it)
    EXPECT_TRUE(names.count((*it)[1])) << "the README names 'accelbench " << (*it)[1] << "', which --help lacks";
}

TEST(Readme, EveryLinkedFileExists) {
  const std::string text = readme();
  const std::regex link(R"(\]\(([^)#:]+)(#[^)]*)?\))");
  int links = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), link); it != std::sregex_iterator(); ++it) {
    ++links;
    const std::string target = (*it)[1];
    EXPECT_TRUE(std::filesystem::exists(std::string(ACCELBENCH_SOURCE_DIR) + "/" + target))
        << "README.md links to " << target << ", which does not exist";
  }
  EXPECT_GE(links, 5);
}

}  // namespace
