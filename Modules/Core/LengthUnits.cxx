#include "LengthUnits.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace thintissue
{

namespace
{

struct NamedUnit
{
  const char* name;
  double metresPerUnit;
  const char* spelled; ///< singular, British; "-er" and "s" forms follow
};

// In the order detection tries them: the commonest unit first.
constexpr NamedUnit NamedUnits[] = {
  { "mm", 0.001, "millimetre" },
  { "m", 1.0, "metre" },
  { "cm", 0.01, "centimetre" },
  { "um", 1e-6, "micrometre" },
};

std::string lowered(const std::string& text)
{
  std::string result = text;
  std::transform(result.begin(),
    result.end(),
    result.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return result;
}

std::string shortNumber(double value)
{
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

} // namespace

std::string LengthUnits::description() const
{
  return name.empty() ? "1 unit = " + shortNumber(metresPerUnit) + " m" : name;
}

std::optional<LengthUnits> lengthUnitsNamed(const std::string& name)
{
  std::string key = lowered(name);
  if (key == "\xC2\xB5m" || key == "\xCE\xBCm" || key == "micron" || key == "microns")
  {
    key = "um"; // micro sign or Greek mu
  }
  for (const NamedUnit& unit : NamedUnits)
  {
    const std::string metre = unit.spelled;
    const std::string meter = metre.substr(0, metre.size() - 2) + "er";
    if (key == unit.name || key == metre || key == metre + "s" || key == meter ||
        key == meter + "s")
    {
      return LengthUnits{ unit.name, unit.metresPerUnit };
    }
  }
  return std::nullopt;
}

LengthUnits lengthUnitsOfScale(double metresPerUnit)
{
  if (!(metresPerUnit > 0.0) || !std::isfinite(metresPerUnit))
  {
    throw InvalidInputError("length units: the scale (metres per unit) must be positive, not " +
                            shortNumber(metresPerUnit));
  }
  for (const NamedUnit& unit : NamedUnits)
  {
    if (std::abs(metresPerUnit / unit.metresPerUnit - 1.0) <= 1e-9)
    {
      return LengthUnits{ unit.name, unit.metresPerUnit };
    }
  }
  return LengthUnits{ "", metresPerUnit };
}

DetectedLengthUnits detectLengthUnits(double largestExtent)
{
  const std::string extent = "largest extent " + shortNumber(largestExtent);
  for (const NamedUnit& unit : NamedUnits)
  {
    const double metres = largestExtent * unit.metresPerUnit;
    if (metres >= TissueSizeRange[0] && metres <= TissueSizeRange[1])
    {
      return { LengthUnits{ unit.name, unit.metresPerUnit },
        extent + ": a tissue of " + shortNumber(metres * 1000.0) + " mm",
        true };
    }
  }
  return { LengthUnits{},
    extent + " fits no unit for a tissue of 5 mm to 0.5 m; millimetres assumed",
    false };
}

} // namespace thintissue
