#include "CollisionSplitHistory.h"

#include "SplitFormula.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <numeric>
#include <string>

namespace thintissue
{

CollisionSplitHistory::CollisionSplitHistory(std::size_t triangleCount)
  : Nodes(triangleCount)
  , Current(triangleCount)
{
  for (std::size_t t = 0; t < triangleCount; ++t)
    Nodes[t].triangle = static_cast<int>(t);
  std::iota(Current.begin(), Current.end(), 0);
}

void CollisionSplitHistory::check(const CollisionTriangleSplit& split,
  int known,
  const std::vector<Vector3>& restPositions)
{
  const auto fail = [&](const std::string& what)
  {
    throw InvalidInputError(
      "collision split history: split of triangle " + std::to_string(split.parent) + ": " + what);
  };
  if (split.parent < 0 || split.parent >= known)
    fail("not a triangle of the history (" + std::to_string(known) + " triangles)");
  if (split.children.empty() || split.children.front() != split.parent ||
      split.childCorners.size() != split.children.size())
    fail("its first piece must reuse its index, with one corner matrix per piece");
  for (std::size_t c = 1; c < split.children.size(); ++c)
    if (split.children[c] < 0 || split.children[c] > known + static_cast<int>(c) - 1)
      fail("piece " + std::to_string(split.children[c]) + " skips past the triangles known");
  for (int corner : split.parentCorners)
    if (corner < 0 || corner >= static_cast<int>(restPositions.size()))
      fail("corner " + std::to_string(corner) + " has no rest position");
}

void CollisionSplitHistory::recordSplit(const CollisionTriangleSplit& split,
  const std::vector<Vector3>& restPositions)
{
  check(split, static_cast<int>(Current.size()), restPositions);
  record(split, restPositions);
}

void CollisionSplitHistory::recordCut(const CollisionCutResult& cut,
  const std::vector<Vector3>& restPositions)
{
  // All checked before any is recorded: a refused cut changes nothing.
  int known = static_cast<int>(Current.size());
  for (const CollisionTriangleSplit& split : cut.splits)
  {
    check(split, known, restPositions);
    for (int child : split.children)
      known = std::max(known, child + 1);
  }
  std::size_t pieces = 0;
  for (const CollisionTriangleSplit& split : cut.splits)
    pieces += split.children.size();
  // Room for the cut at once, growing geometrically (a cut's splits had
  // each grown the arrays of a fresh history).
  const auto room = [](auto& list, std::size_t more)
  {
    if (list.capacity() < list.size() + more)
      list.reserve(std::max(list.size() + more, 2 * list.capacity()));
  };
  room(Nodes, pieces);
  room(Pieces, pieces);
  room(Maps, pieces);
  room(Offsets, pieces);
  room(ChildNodes, pieces);
  room(Splits, cut.splits.size());
  for (const CollisionTriangleSplit& split : cut.splits)
    record(split, restPositions);
}

void CollisionSplitHistory::record(const CollisionTriangleSplit& split,
  const std::vector<Vector3>& restPositions)
{
  Split record;
  record.frame = planarFrame(restPositions, split.parentCorners);
  record.firstPiece = static_cast<int>(Pieces.size());
  record.pieceCount = static_cast<int>(split.children.size());
  const std::vector<Eigen::Matrix3d> inverses = childInverses(split);
  for (std::size_t c = 0; c < split.children.size(); ++c)
  {
    const auto& corners = split.childCorners[c];
    Pieces.push_back(planePiece({ { planarPoint(record.frame, corners[0]),
      planarPoint(record.frame, corners[1]),
      planarPoint(record.frame, corners[2]) } }));
    const PlaneToChild toChild(record.frame, inverses[c]);
    Maps.push_back(toChild.map());
    Offsets.push_back(toChild.offset());
  }
  const int parentNode = Current[static_cast<std::size_t>(split.parent)];
  Nodes[static_cast<std::size_t>(parentNode)].split = static_cast<int>(Splits.size());
  for (int child : split.children)
  {
    const int node = static_cast<int>(Nodes.size());
    Nodes.push_back({ child, -1 });
    if (child >= static_cast<int>(Current.size()))
      Current.resize(static_cast<std::size_t>(child) + 1, -1);
    Current[static_cast<std::size_t>(child)] = node;
    ChildNodes.push_back(node);
  }
  Splits.push_back(record);
}

CollisionSplitHistory::Resolved CollisionSplitHistory::resolve(int node,
  const Vector3& parameters) const
{
  Resolved resolved{ node, parameters };
  for (int s = Nodes[static_cast<std::size_t>(node)].split; s >= 0;
       s = Nodes[static_cast<std::size_t>(resolved.node)].split)
  {
    const Split& split = Splits[static_cast<std::size_t>(s)];
    const Vector2 p = planarPoint(split.frame, resolved.parameters);
    const int piece = split.firstPiece + pieceContaining(Pieces.data() + split.firstPiece,
                                           static_cast<std::size_t>(split.pieceCount),
                                           p);
    resolved.parameters = PlaneToChild::apply(Maps[piece], Offsets[piece], p);
    resolved.node = ChildNodes[static_cast<std::size_t>(piece)];
  }
  return resolved;
}

} // namespace thintissue
