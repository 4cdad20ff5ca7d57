#include "vtkThinTissueMeshReader.h"

#include "MeshImport.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkCommand.h>
#include <vtkDataSetReader.h>
#include <vtkGeometryFilter.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>

vtkStandardNewMacro(vtkThinTissueMeshReader);

namespace
{

const char* const VTKFormats[] = { ".vtp", ".vtk", ".vtu" };

/// Collects the error messages VTK readers emit instead of throwing.
class ReaderErrorObserver : public vtkCommand
{
public:
  static ReaderErrorObserver* New() { return new ReaderErrorObserver; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    if (this->Message.empty() && callData != nullptr)
    {
      this->Message = static_cast<const char*>(callData);
    }
  }
  std::string Message;
};

/// Reads a VTK-format file and returns its outer surface as polydata.
vtkSmartPointer<vtkPolyData> readVTKFormat(const std::string& path, const std::string& extension)
{
  vtkNew<ReaderErrorObserver> errors;
  vtkSmartPointer<vtkAlgorithm> reader;
  if (extension == ".vtp" || extension == ".vtu")
  {
    vtkSmartPointer<vtkXMLReader> xml;
    if (extension == ".vtp")
    {
      xml = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    }
    else
    {
      xml = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    }
    if (!xml->CanReadFile(path.c_str()))
    {
      throw thintissue::FileError(path,
        std::string("cannot be parsed: not a VTK XML ") +
          (extension == ".vtp" ? "PolyData" : "UnstructuredGrid") + " file");
    }
    // XML errors are raised by internal objects; route them to the observer.
    xml->SetReaderErrorObserver(errors);
    xml->SetParserErrorObserver(errors);
    xml->SetFileName(path.c_str());
    reader = xml;
  }
  else
  {
    auto legacy = vtkSmartPointer<vtkDataSetReader>::New();
    legacy->SetFileName(path.c_str());
    reader = legacy;
  }
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  // The surface filter turns any data set (polydata too) into polydata.
  vtkNew<vtkGeometryFilter> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  surface->AddObserver(vtkCommand::ErrorEvent, errors);
  surface->Update();
  if (!errors->Message.empty())
  {
    std::string message = errors->Message;
    message.erase(message.find_last_not_of(" \n") + 1);
    throw thintissue::FileError(path, "cannot be parsed: " + message);
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(surface->GetOutput());
  return output;
}

} // namespace

vtkThinTissueMeshReader::vtkThinTissueMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkThinTissueMeshReader::~vtkThinTissueMeshReader()
{
  this->SetFileName(nullptr);
}

bool vtkThinTissueMeshReader::CanReadFileExtension(const char* fileName)
{
  if (fileName == nullptr)
  {
    return false;
  }
  const std::string extension = thintissue::lowerCaseExtension(fileName);
  const auto& kernel = thintissue::kernelMeshFormats();
  return std::find(kernel.begin(), kernel.end(), extension) != kernel.end() ||
         std::find(std::begin(VTKFormats), std::end(VTKFormats), extension) != std::end(VTKFormats);
}

int vtkThinTissueMeshReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastErrorMessage.clear();
  try
  {
    if (this->FileName == nullptr || this->FileName[0] == '\0')
    {
      throw thintissue::Error("vtkThinTissueMeshReader: no FileName set");
    }
    const std::string path = this->FileName;
    const std::string extension = thintissue::lowerCaseExtension(path);
    this->UpdateProgress(0.0);
    thintissue::TriangleMesh mesh;
    if (std::find(std::begin(VTKFormats), std::end(VTKFormats), extension) != std::end(VTKFormats))
    {
      thintissue::checkReadableFile(path);
      vtkSmartPointer<vtkPolyData> surface = readVTKFormat(path, extension);
      try
      {
        mesh = thintissue::fromPolyData(surface, path);
      }
      catch (const thintissue::InvalidInputError& error)
      {
        throw thintissue::FileError(path, error.what());
      }
      if (mesh.triangles.empty())
      {
        throw thintissue::FileError(path, "contains no triangles (empty mesh)");
      }
    }
    else
    {
      thintissue::MeshImportOptions options;
      options.weldCoincidentVertices = this->WeldCoincidentVertices;
      mesh = thintissue::readTriangleMesh(path, options);
    }
    this->UpdateProgress(0.8);
    output->ShallowCopy(thintissue::toPolyData(mesh));
    vtkLogF(TRACE,
      "read '%s': %zu vertices, %zu triangles",
      path.c_str(),
      mesh.vertexCount(),
      mesh.triangleCount());
    this->UpdateProgress(1.0);
    return 1;
  }
  catch (const std::exception& error)
  {
    this->LastErrorMessage = error.what();
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }
}

void vtkThinTissueMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "WeldCoincidentVertices: " << this->WeldCoincidentVertices << "\n";
  os << indent << "LastErrorMessage: " << this->LastErrorMessage << "\n";
}
