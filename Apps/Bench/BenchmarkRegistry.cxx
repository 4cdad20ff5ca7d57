#include "BenchmarkRegistry.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>

namespace thintissue::bench
{

BenchmarkReporter::BenchmarkReporter(std::ostream& out, std::string suite)
  : Out(out)
  , Suite(std::move(suite))
{
}

void BenchmarkReporter::report(const std::string& caseName,
  const std::string& metric,
  double value,
  const std::string& unit,
  std::optional<double> thesis)
{
  // ordered_json keeps the documented field order.
  nlohmann::ordered_json line = { { "suite", Suite },
    { "case", caseName },
    { "metric", metric },
    { "value", value },
    { "unit", unit },
    { "thesis", nullptr } };
  if (thesis)
  {
    line["thesis"] = *thesis;
  }
  Out << line.dump() << std::endl;
}

void BenchmarkReporter::skip(const std::string& caseName, const std::string& reason)
{
  std::cerr << "ThinTissueBench: " << Suite << "/" << caseName << " skipped: " << reason << "\n";
}

std::vector<BenchmarkSuite>& benchmarkSuites()
{
  static std::vector<BenchmarkSuite> suites;
  return suites;
}

BenchmarkSuiteRegistration::BenchmarkSuiteRegistration(const std::string& name,
  const std::string& description,
  BenchmarkSuiteFunction run)
{
  benchmarkSuites().push_back({ name, description, std::move(run) });
}

double medianSeconds(const std::function<void()>& work, int repetitions, bool warmUp)
{
  if (warmUp)
  {
    work();
  }
  std::vector<double> seconds;
  for (int r = 0; r < std::max(1, repetitions); ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    work();
    seconds.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

double percentile(std::vector<double> values, double fraction)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size()));
  return values[std::min(values.size() - 1, index)];
}

} // namespace thintissue::bench
