// VTK sources of the procedural tissues: ports, arrays, multiblock, errors.
#include "vtkKneeBoneSource.h"
#include "vtkKneeSceneSource.h"
#include "vtkKneeTissueSource.h"
#include "vtkMeniscusSource.h"
#include "vtkSurgicalInstrumentSource.h"
#include "vtkThinSheetSource.h"

#include "ThinTissueTestSupport.h"

#include <vtkCellData.h>
#include <vtkCellTypes.h>
#include <vtkCommand.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "ThinTissueVtkErrorObserver.h"

#include <gtest/gtest.h>

#include <sstream>

namespace
{
using thintissue::testing::ErrorCounter;

std::string blockName(vtkMultiBlockDataSet* all, unsigned int b)
{
  return all->GetMetaData(b)->Get(vtkCompositeDataSet::NAME());
}
} // namespace

TEST(vtkThinSheetSource, OutputsTheThreeMeshesAndTheMultiblock)
{
  vtkNew<vtkThinSheetSource> sheet;
  sheet->SetThesisVisualModel(1);
  sheet->Update();
  vtkPolyData* visual = sheet->GetVisualOutput();
  EXPECT_EQ(visual->GetNumberOfPolys(), 1676);
  EXPECT_NE(visual->GetPointData()->GetNormals(), nullptr);
  EXPECT_NE(visual->GetCellData()->GetArray("CornerTextureCoordinates"), nullptr);
  vtkPolyData* collision = sheet->GetCollisionOutput();
  EXPECT_EQ(collision->GetNumberOfPoints(), 67);
  vtkDataArray* radius = collision->GetPointData()->GetArray("Radius");
  ASSERT_NE(radius, nullptr);
  EXPECT_DOUBLE_EQ(radius->GetTuple1(0), 1.0);
  vtkUnstructuredGrid* hexahedra = sheet->GetSimulationOutput();
  EXPECT_EQ(hexahedra->GetNumberOfCells(), 81);
  EXPECT_EQ(hexahedra->GetNumberOfPoints(), 200);
  EXPECT_EQ(hexahedra->GetCellType(0), VTK_HEXAHEDRON);
  EXPECT_NE(hexahedra->GetPointData()->GetArray("FixedNode"), nullptr);
  vtkMultiBlockDataSet* all = sheet->GetAllMeshesOutput();
  ASSERT_EQ(all->GetNumberOfBlocks(), 3u);
  EXPECT_EQ(blockName(all, 0), "Visual");
  EXPECT_EQ(blockName(all, 1), "Collision");
  EXPECT_EQ(blockName(all, 2), "Simulation");
  EXPECT_EQ(vtkPolyData::SafeDownCast(all->GetBlock(0))->GetNumberOfPolys(), 1676);
  std::ostringstream print;
  sheet->Print(print);
  EXPECT_NE(print.str().find("Thickness: 2"), std::string::npos);
}

TEST(vtkThinSheetSource, BadParametersReportAnErrorAndEmptyOutputs)
{
  vtkNew<vtkThinSheetSource> sheet;
  vtkNew<ErrorCounter> errors;
  sheet->AddObserver(vtkCommand::ErrorEvent, errors);
  sheet->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  sheet->SetThickness(500.0);
  sheet->Update();
  EXPECT_GE(errors->count, 1);
  EXPECT_NE(errors->all.find("thickness"), std::string::npos) << errors->all;
  EXPECT_EQ(sheet->GetVisualOutput()->GetNumberOfPoints(), 0);
  // Fixing the parameter recovers.
  sheet->SetThickness(2.0);
  sheet->Update();
  EXPECT_GT(sheet->GetVisualOutput()->GetNumberOfPoints(), 0);
}

TEST(vtkMeniscusSource, IntactAndTornWithMonitorPoints)
{
  vtkNew<vtkMeniscusSource> meniscus;
  meniscus->Update();
  EXPECT_EQ(meniscus->GetCollisionOutput()->GetNumberOfPoints(), 105);
  EXPECT_EQ(meniscus->GetSimulationOutput()->GetNumberOfCells(), 42);
  vtkPolyData* monitor = meniscus->GetMonitorPointsOutput();
  EXPECT_EQ(monitor->GetNumberOfLines(), 1);
  EXPECT_GT(monitor->GetNumberOfPoints(), 8);
  ASSERT_NE(monitor->GetPointData()->GetArray("RegionPoint"), nullptr);
  EXPECT_EQ(monitor->GetPointData()->GetArray("RegionPoint")->GetNumberOfComponents(), 3);
  ASSERT_NE(monitor->GetPointData()->GetArray("Thickness"), nullptr);
  EXPECT_EQ(meniscus->GetAllMeshesOutput()->GetNumberOfBlocks(), 4u);
  EXPECT_EQ(blockName(meniscus->GetAllMeshesOutput(), 3), "MonitorPoints");
  const vtkIdType intactPoints = meniscus->GetCollisionOutput()->GetNumberOfPoints();

  meniscus->SetTearType(vtkMeniscusSource::LongitudinalTear);
  meniscus->SetMonitorPointSpacing(0.25);
  meniscus->Update();
  EXPECT_GT(meniscus->GetCollisionOutput()->GetNumberOfPoints(), intactPoints);
  EXPECT_EQ(meniscus->GetMonitorPointsOutput()->GetNumberOfLines(), 2);
  EXPECT_GT(meniscus->GetMonitorPointsOutput()->GetNumberOfPoints(), 200);

  meniscus->SetExaminationResolution();
  meniscus->SetTearType(vtkMeniscusSource::NoTear);
  meniscus->Update();
  EXPECT_NEAR(meniscus->GetVisualOutput()->GetNumberOfPolys(), 6096, 0.05 * 6096);
}

TEST(vtkMeniscusSource, BadTearIsReported)
{
  vtkNew<vtkMeniscusSource> meniscus;
  vtkNew<ErrorCounter> errors;
  meniscus->AddObserver(vtkCommand::ErrorEvent, errors);
  meniscus->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  meniscus->SetTearType(7);
  EXPECT_EQ(errors->count, 1);
  EXPECT_EQ(meniscus->GetTearType(), vtkMeniscusSource::NoTear);
  meniscus->SetTearType(vtkMeniscusSource::RadialTear);
  meniscus->SetTearAcross(1.5);
  meniscus->Update();
  EXPECT_GE(errors->count, 2);
  EXPECT_NE(errors->all.find("tear"), std::string::npos) << errors->all;
}

TEST(vtkMeniscusSource, WritesAndReadsBackAsVtp)
{
  vtkNew<vtkMeniscusSource> meniscus;
  const std::string path =
    (thintissue::testing::temporaryDirectory() / "meniscus-visual.vtp").string();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(meniscus->GetOutputPort(0));
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(
    reader->GetOutput()->GetNumberOfPolys(), meniscus->GetVisualOutput()->GetNumberOfPolys());
}

TEST(vtkSurgicalInstrumentSource, OutputsVisualCentreLineAndWorkingFeatures)
{
  vtkNew<vtkSurgicalInstrumentSource> instrument;
  for (int type = vtkSurgicalInstrumentSource::ProbeHook;
       type <= vtkSurgicalInstrumentSource::Scalpel;
       ++type)
  {
    instrument->SetInstrumentType(type);
    instrument->Update();
    vtkPolyData* visual = instrument->GetOutput(vtkSurgicalInstrumentSource::VisualPort);
    EXPECT_GT(visual->GetNumberOfPolys(), 500) << type;
    EXPECT_NE(visual->GetPointData()->GetArray("InstrumentPart"), nullptr);
    vtkPolyData* collision = instrument->GetOutput(vtkSurgicalInstrumentSource::CollisionPort);
    EXPECT_GE(collision->GetNumberOfLines(), 1) << type;
    vtkDataArray* radius = collision->GetCellData()->GetArray("Radius");
    ASSERT_NE(radius, nullptr);
    EXPECT_GT(radius->GetRange()[0], 0.0);
    vtkPolyData* features = instrument->GetOutput(vtkSurgicalInstrumentSource::WorkingFeaturesPort);
    EXPECT_EQ(features->GetNumberOfVerts(), 1);
    // The tip is the tool frame's origin.
    double tip[3];
    features->GetPoint(0, tip);
    EXPECT_NEAR(tip[0] * tip[0] + tip[1] * tip[1] + tip[2] * tip[2], 0.0, 1e-12);
    const bool hasEdgeOrOutline = type != vtkSurgicalInstrumentSource::ProbeHook;
    EXPECT_EQ(features->GetNumberOfLines() > 0, hasEdgeOrOutline) << type;
  }
  instrument->SetInstrumentTypeByName("Large Shaver");
  EXPECT_EQ(instrument->GetInstrumentType(), vtkSurgicalInstrumentSource::LargeShaver);
  vtkNew<ErrorCounter> errors;
  instrument->AddObserver(vtkCommand::ErrorEvent, errors);
  instrument->SetInstrumentTypeByName("chainsaw");
  EXPECT_EQ(errors->count, 1);
  EXPECT_NE(errors->all.find("probe_hook"), std::string::npos) << errors->all;
  EXPECT_EQ(instrument->GetInstrumentType(), vtkSurgicalInstrumentSource::LargeShaver);
}

TEST(vtkKneeSources, SceneBlocksTissueSettingsAndBones)
{
  vtkNew<vtkKneeSceneSource> knee;
  knee->Update();
  vtkMultiBlockDataSet* scene = knee->GetOutput();
  const char* expected[6] = { "Tibia",
    "Femur",
    "TibialCartilage",
    "AnteriorCruciateLigament",
    "PosteriorCruciateLigament",
    "MedialMeniscus" };
  ASSERT_EQ(scene->GetNumberOfBlocks(), 6u);
  for (unsigned int b = 0; b < 6; ++b)
  {
    EXPECT_EQ(blockName(scene, b), expected[b]);
    auto* meshes = vtkMultiBlockDataSet::SafeDownCast(scene->GetBlock(b));
    ASSERT_NE(meshes, nullptr);
    EXPECT_EQ(meshes->GetNumberOfBlocks(), b < 2 ? 2u : 3u) << expected[b];
    EXPECT_GT(vtkPolyData::SafeDownCast(meshes->GetBlock(0))->GetNumberOfPolys(), 1000);
  }

  vtkNew<vtkKneeTissueSource> ligament;
  ligament->SetTissue(vtkKneeTissueSource::PosteriorCruciateLigament);
  ligament->SetCollisionSetting(4);
  ligament->Update();
  EXPECT_EQ(ligament->GetCollisionOutput()->GetNumberOfPoints(), 45); // table 5-7
  EXPECT_NE(ligament->GetCollisionOutput()->GetPointData()->GetArray("Radius"), nullptr);
  ligament->SetCollisionSetting(2);
  ligament->Update();
  EXPECT_NEAR(ligament->GetCollisionOutput()->GetNumberOfPolys(), 2000, 100);
  // Closed collision surfaces carry radius 0 (no thickness to add).
  vtkDataArray* closedRadius = ligament->GetCollisionOutput()->GetPointData()->GetArray("Radius");
  ASSERT_NE(closedRadius, nullptr);
  EXPECT_EQ(closedRadius->GetRange()[1], 0.0);

  vtkNew<vtkKneeTissueSource> cartilage;
  cartilage->SetTissue(vtkKneeTissueSource::TibialCartilage);
  for (int setting = 2; setting <= 4; ++setting)
  {
    cartilage->SetCollisionSetting(setting);
    cartilage->Update();
    const double thesis[3] = { 1000, 500, 100 }; // fig. 5-27
    EXPECT_NEAR(cartilage->GetCollisionOutput()->GetNumberOfPolys(),
      thesis[setting - 2],
      0.05 * thesis[setting - 2]);
  }

  vtkNew<vtkKneeBoneSource> bone;
  bone->SetBone(vtkKneeBoneSource::Femur);
  bone->Update();
  EXPECT_NEAR(bone->GetOutput(0)->GetNumberOfPoints(), 5850, 0.05 * 5850); // table 6-2
  EXPECT_NEAR(bone->GetOutput(1)->GetNumberOfPoints(), 59, 0.05 * 59);

  vtkNew<ErrorCounter> errors;
  knee->AddObserver(vtkCommand::ErrorEvent, errors);
  knee->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  knee->SetJointGap(-1.0);
  knee->Update();
  EXPECT_NE(errors->all.find("joint gap"), std::string::npos) << errors->all;
}
