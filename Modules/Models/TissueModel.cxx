#include "TissueModel.h"

namespace thintissue
{

const std::vector<double>& TissueModel::collisionRadii() const
{
  return collision.pointAttributes.get(CollisionRadiusArrayName).values;
}

} // namespace thintissue
