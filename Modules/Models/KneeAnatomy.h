// One anatomical frame for every knee model, so that the procedural tibia,
// femur, cartilage, menisci, ligaments and the instruments fit together
// without a registration step.
//
// Right knee in extension, millimetres. +x lateral, +y anterior, +z proximal.
// The origin is the centre of the tibial plateau on the subchondral bone
// surface; the intercondylar eminence lies on x = 0.
#ifndef KneeAnatomy_h
#define KneeAnatomy_h

#include "TriangleMesh.h"

namespace thintissue
{
namespace knee
{

/// Centres of the two tibial compartments on the subchondral bone (z = 0).
inline Vector3 medialCompartmentCentre()
{
  return Vector3(-22.0, 0.0, 0.0);
}
inline Vector3 lateralCompartmentCentre()
{
  return Vector3(22.0, 0.0, 0.0);
}

/// Thickness of the tibial articular cartilage at the compartment centre.
constexpr double TibialCartilageThickness = 2.0;
/// Height of the menisci's tibial (lower) surface: they rest on the cartilage.
constexpr double MeniscusBaseHeight = TibialCartilageThickness;
/// Distance between tibial cartilage and femoral cartilage at the
/// compartment centres: the compartment as opened by valgus stress during
/// arthroscopy (a closed joint leaves no room for camera and instrument).
constexpr double DefaultJointGap = 4.0;
/// Thickness of the femoral articular cartilage.
constexpr double FemoralCartilageThickness = 2.0;

} // namespace knee
} // namespace thintissue

#endif
