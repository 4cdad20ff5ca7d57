/**
 * @class vtkThinTissueMeshReader
 * @brief Reads a triangle surface from OBJ, STL, PLY, OFF, glTF, FBX, VTP,
 * VTK or VTU into vtkPolyData with welded positions.
 *
 * Polygons are triangulated. Texture coordinates are kept per triangle
 * corner in the cell array "CornerTextureCoordinates" (and as point TCoords
 * where the texture has no seam). On bad input (missing file, a directory,
 * unknown format, malformed content, empty mesh, NaN coordinates, indices out
 * of range) the reader reports an error naming the file and the problem,
 * produces an empty output and keeps the message in GetLastErrorMessage().
 */
#ifndef vtkThinTissueMeshReader_h
#define vtkThinTissueMeshReader_h

#include "ThinTissueVTKCoreModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class THINTISSUEVTKCORE_EXPORT vtkThinTissueMeshReader : public vtkPolyDataAlgorithm
{
public:
  static vtkThinTissueMeshReader* New();
  vtkTypeMacro(vtkThinTissueMeshReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Merge vertices at identical positions for formats that split them
  /// (STL, and assimp's loaders at texture seams). On by default.
  vtkSetMacro(WeldCoincidentVertices, bool);
  vtkGetMacro(WeldCoincidentVertices, bool);
  vtkBooleanMacro(WeldCoincidentVertices, bool);
  ///@}

  /// The message of the last failed read, or "" after a successful one.
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

  /// True if the extension of `fileName` is one this reader handles.
  static bool CanReadFileExtension(const char* fileName);

protected:
  vtkThinTissueMeshReader();
  ~vtkThinTissueMeshReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  bool WeldCoincidentVertices = true;
  std::string LastErrorMessage;

private:
  vtkThinTissueMeshReader(const vtkThinTissueMeshReader&) = delete;
  void operator=(const vtkThinTissueMeshReader&) = delete;
};

#endif
