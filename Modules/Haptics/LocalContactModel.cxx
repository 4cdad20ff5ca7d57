#include "LocalContactModel.h"

#include "CollisionScene.h"

#include <algorithm>

namespace thintissue
{

Vector3 LocalContactModel::force(const RigidPose& pose) const
{
  // Instrument motion since publication, applied to each contact point.
  const Eigen::Matrix3d rotation = pose.rotation;
  Vector3 total = Vector3::Zero();
  for (int c = 0; c < count; ++c)
  {
    const LocalContact& contact = contacts[c];
    const Vector3 published = toolPose * contact.toolPoint;
    const Vector3 now = rotation * contact.toolPoint + pose.translation;
    // Moving against the normal deepens the contact.
    const double depth = contact.depth - (now - published).dot(contact.normal);
    if (depth > 0.0)
    {
      total += contact.stiffness * depth * contact.normal;
    }
  }
  return total;
}

bool LocalContactModel::add(const LocalContact& contact)
{
  if (count >= MaximumContacts)
  {
    return false;
  }
  contacts[count++] = contact;
  return true;
}

void fillLocalContactModel(const CollisionScene& scene,
  const RigidTool& tool,
  int toolIndex,
  double time,
  LocalContactModel& model)
{
  model.time = time;
  model.toolPose = tool.pose();
  model.count = 0;
  const Eigen::Matrix3d toTool = tool.pose().rotation.transpose();
  for (const SceneContact& c : scene.contacts())
  {
    const bool first = c.first.kind == SceneBodyKind::Tool && c.first.index == toolIndex;
    const bool second = c.second.kind == SceneBodyKind::Tool && c.second.index == toolIndex;
    if (!first && !second)
    {
      continue;
    }
    // `normal` pushes `first` out of `second`.
    LocalContact contact;
    const Vector3 point = first ? c.pointOnFirst : c.pointOnSecond;
    contact.toolPoint = toTool * (point - tool.pose().translation);
    contact.normal = first ? c.normal : Vector3(-c.normal);
    contact.depth = c.depth;
    contact.stiffness = c.stiffness;
    if (!model.add(contact))
    {
      // Full: replace the shallowest if this one is deeper.
      auto shallowest = std::min_element(model.contacts.begin(),
        model.contacts.end(),
        [](const LocalContact& a, const LocalContact& b) { return a.depth < b.depth; });
      if (shallowest->depth < contact.depth)
      {
        *shallowest = contact;
      }
    }
  }
}

} // namespace thintissue
