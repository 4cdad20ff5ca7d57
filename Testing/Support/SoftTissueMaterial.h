// The soft test material of the solver and cutting tests (mm, N, s): a
// compliant tissue that moves visibly under forces of 1e-4 N.
#ifndef SoftTissueMaterial_h
#define SoftTissueMaterial_h

#include "HexahedronElement.h"

namespace thintissue::test
{

inline LinearMaterial softTissue()
{
  LinearMaterial material;
  material.youngModulus = 0.5;
  material.poissonRatio = 0.45;
  material.density = 1.0e-9;
  return material;
}

} // namespace thintissue::test

#endif
