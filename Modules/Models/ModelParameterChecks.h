// Checks of procedural-model parameters with errors that name the model and
// the parameter ("meniscus: rim height must be a positive number (got 0)").
// Private to the Models module.
#ifndef ModelParameterChecks_h
#define ModelParameterChecks_h

#include "ThinTissueError.h"

#include <cmath>
#include <sstream>
#include <string>

namespace thintissue::detail
{

class ParameterChecks
{
public:
  explicit ParameterChecks(std::string model)
    : Model(std::move(model))
  {
  }

  [[noreturn]] void fail(const std::string& problem) const
  {
    throw InvalidInputError(Model + ": " + problem);
  }

  void requirePositive(double value, const std::string& what) const
  {
    if (!(value > 0.0) || !std::isfinite(value))
    {
      std::ostringstream message;
      message << what << " must be a positive number (got " << value << ")";
      fail(message.str());
    }
  }

  void requireAtLeast(int value, int minimum, const std::string& what) const
  {
    if (value < minimum)
    {
      std::ostringstream message;
      message << what << " must be at least " << minimum << " (got " << value << ")";
      fail(message.str());
    }
  }

private:
  std::string Model;
};

} // namespace thintissue::detail

#endif
