// Benchmark harness of ThinTissueBench. A suite is a function that measures
// and reports cases; each report is printed at once as one JSON line
//   {"suite":…,"case":…,"metric":…,"value":…,"unit":…,"thesis":…}
// where "thesis" is the figure the thesis reports for the same work, or null.
// Add a suite in its own file with THINTISSUE_BENCHMARK_SUITE.
#ifndef BenchmarkRegistry_h
#define BenchmarkRegistry_h

#include <chrono>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace thintissue::bench
{

/// Options every suite sees.
struct BenchmarkContext
{
  /// Small sizes and few repetitions: a smoke run for the test suite.
  bool quick = false;
  /// ../shared/data (or $THINTISSUE_SHARED_DATA); may not exist.
  std::string sharedDataDirectory;
  /// Directory for scratch files.
  std::string temporaryDirectory;
};

class BenchmarkReporter
{
public:
  BenchmarkReporter(std::ostream& out, std::string suite);
  void report(const std::string& caseName,
    const std::string& metric,
    double value,
    const std::string& unit,
    std::optional<double> thesis = std::nullopt);
  /// A case that could not run (e.g. missing optional data), on stderr.
  void skip(const std::string& caseName, const std::string& reason);

private:
  std::ostream& Out;
  std::string Suite;
};

using BenchmarkSuiteFunction = std::function<void(const BenchmarkContext&, BenchmarkReporter&)>;

struct BenchmarkSuite
{
  std::string name;
  std::string description;
  BenchmarkSuiteFunction run;
};

std::vector<BenchmarkSuite>& benchmarkSuites();

struct BenchmarkSuiteRegistration
{
  BenchmarkSuiteRegistration(const std::string& name,
    const std::string& description,
    BenchmarkSuiteFunction run);
};

#define THINTISSUE_BENCHMARK_SUITE(identifier, name, description)                                  \
  static void identifier(                                                                          \
    const ::thintissue::bench::BenchmarkContext&, ::thintissue::bench::BenchmarkReporter&);        \
  static const ::thintissue::bench::BenchmarkSuiteRegistration identifier##Registration(           \
    name, description, identifier);                                                                \
  static void identifier

/// Median wall time in seconds of `repetitions` runs of `work` (after one
/// warm-up run when `warmUp`).
double medianSeconds(const std::function<void()>& work, int repetitions, bool warmUp = true);

/// The value below which `fraction` of `values` lie (1: the largest); 0 for
/// none.
double percentile(std::vector<double> values, double fraction);

} // namespace thintissue::bench

#endif
