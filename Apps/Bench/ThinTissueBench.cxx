// ThinTissueBench: runs the benchmark suites and prints one JSON object per
// line per case. Usage:
//   ThinTissueBench [--list] [--suite NAME]... [--quick] [--data DIR]
#include "BenchmarkRegistry.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>

int main(int argc, char* argv[])
{
  using namespace thintissue::bench;
  BenchmarkContext context;
  const char* environmentData = std::getenv("THINTISSUE_SHARED_DATA");
  context.sharedDataDirectory = environmentData ? environmentData : THINTISSUE_DEFAULT_SHARED_DATA;
  context.temporaryDirectory = std::filesystem::temp_directory_path().string();
  std::vector<std::string> selected;
  bool list = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--list")
    {
      list = true;
    }
    else if (argument == "--quick")
    {
      context.quick = true;
    }
    else if (argument == "--suite" && i + 1 < argc)
    {
      selected.push_back(argv[++i]);
    }
    else if (argument == "--data" && i + 1 < argc)
    {
      context.sharedDataDirectory = argv[++i];
    }
    else
    {
      std::cerr << "usage: ThinTissueBench [--list] [--suite NAME]... [--quick] [--data DIR]\n";
      return 2;
    }
  }

  auto suites = benchmarkSuites();
  std::sort(suites.begin(),
    suites.end(),
    [](const BenchmarkSuite& a, const BenchmarkSuite& b) { return a.name < b.name; });
  if (list)
  {
    for (const BenchmarkSuite& suite : suites)
    {
      std::cout << suite.name << "\t" << suite.description << "\n";
    }
    return 0;
  }
  for (const std::string& name : selected)
  {
    if (std::none_of(suites.begin(),
          suites.end(),
          [&](const BenchmarkSuite& suite) { return suite.name == name; }))
    {
      std::cerr << "ThinTissueBench: no suite named '" << name << "' (see --list)\n";
      return 2;
    }
  }
  int failures = 0;
  for (const BenchmarkSuite& suite : suites)
  {
    if (!selected.empty() &&
        std::find(selected.begin(), selected.end(), suite.name) == selected.end())
    {
      continue;
    }
    BenchmarkReporter reporter(std::cout, suite.name);
    try
    {
      suite.run(context, reporter);
    }
    catch (const std::exception& error)
    {
      std::cerr << "ThinTissueBench: suite '" << suite.name << "' failed: " << error.what() << "\n";
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
