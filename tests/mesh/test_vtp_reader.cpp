// The VTP reader (our own parser, modules/mesh/src/io/VtpReader.cpp) against VTK's own writer in every data
// layout it writes, and against the files that crashed, hung or exhausted VTK 9.1's reader (fuzzing, session 26).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"

namespace fs = std::filesystem;
using namespace reamsim;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("reamsim_vtp_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

void writeText(const fs::path& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
}

// A wavy sheet of quads split into triangles, plus one quad and one strip, with coordinates that need all
// of a double's bits.
vtkSmartPointer<vtkPolyData> sheet(int n, bool doublePoints) {
  auto pts = vtkSmartPointer<vtkPoints>::New();
  pts->SetDataTypeToDouble();
  if (!doublePoints) pts->SetDataTypeToFloat();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) pts->InsertNextPoint(i * 0.7 + std::sin(j * 1.3) / 3.0, j * 0.9 + 1.0 / 7.0, std::cos(i * j * 0.1) * 5.0);
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto id = [n](int i, int j) { return vtkIdType(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i == 0 && j == 0) {
        const vtkIdType quad[4] = {id(0, 0), id(1, 0), id(1, 1), id(0, 1)};
        polys->InsertNextCell(4, quad);
        continue;
      }
      const vtkIdType a[3] = {id(i, j), id(i + 1, j), id(i + 1, j + 1)};
      const vtkIdType b[3] = {id(i, j), id(i + 1, j + 1), id(i, j + 1)};
      polys->InsertNextCell(3, a);
      polys->InsertNextCell(3, b);
    }
  auto strips = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType strip[5] = {id(0, 0), id(0, 1), id(1, 0), id(1, 1), id(2, 0)};
  strips->InsertNextCell(5, strip);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetPolys(polys);
  poly->SetStrips(strips);
  return poly;
}

struct Layout {
  const char* name;
  int mode;  // 0 ascii, 1 binary, 2 appended
  bool encodeAppended, compress, uint64Header, bigEndian, doublePoints, int32Ids;
  int blockSize;
};

class VtpLayouts : public ::testing::TestWithParam<Layout> {};

TEST_P(VtpLayouts, ReadsWhatVtkWritesExactly) {
  const Layout& l = GetParam();
  const auto poly = sheet(12, l.doublePoints);
  const fs::path file = scratch(std::string(l.name) + ".vtp");
  auto w = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  w->SetInputData(poly);
  w->SetFileName(file.string().c_str());
  if (l.mode == 0) w->SetDataModeToAscii();
  if (l.mode == 1) w->SetDataModeToBinary();
  if (l.mode == 2) w->SetDataModeToAppended();
  w->SetEncodeAppendedData(l.encodeAppended);
  if (l.compress) w->SetCompressorTypeToZLib();
  else w->SetCompressorTypeToNone();
  if (l.uint64Header) w->SetHeaderTypeToUInt64();
  else w->SetHeaderTypeToUInt32();
  if (l.bigEndian) w->SetByteOrderToBigEndian();
  else w->SetByteOrderToLittleEndian();
  if (l.int32Ids) w->SetIdTypeToInt32();
  else w->SetIdTypeToInt64();
  if (l.blockSize > 0) w->SetBlockSize(l.blockSize);
  ASSERT_EQ(w->Write(), 1);

  const LoadedMesh m = readMesh(file.string(), ReadOptions{Units::Millimetres});
  const vtkIdType np = poly->GetNumberOfPoints();
  ASSERT_EQ(m.mesh.vertices.size(), std::size_t(np));
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3];
    poly->GetPoint(i, p);  // as stored (float points read back as the floats they are)
    EXPECT_EQ(m.mesh.vertices[std::size_t(i)].x, p[0]) << i;
    EXPECT_EQ(m.mesh.vertices[std::size_t(i)].y, p[1]) << i;
    EXPECT_EQ(m.mesh.vertices[std::size_t(i)].z, p[2]) << i;
  }
  // 2·12² − 2 triangles, the quad as two, the 5-point strip as three.
  ASSERT_EQ(m.mesh.triangles.size(), std::size_t(2 * 12 * 12 - 2 + 2 + 3));
  EXPECT_EQ(m.mesh.triangles[1], (Triangle{0, 14, 13}));  // the quad's fan
  EXPECT_EQ(m.mesh.triangles[2], (Triangle{1, 2, 15}));
  EXPECT_EQ(m.mesh.triangles.back(), (Triangle{1, 14, 2}));  // the strip's third, its winding alternated back
}

INSTANTIATE_TEST_SUITE_P(
    AllLayouts, VtpLayouts,
    ::testing::Values(Layout{"ascii", 0, false, false, false, false, true, false, 0},
                      Layout{"ascii_float", 0, false, false, false, false, false, true, 0},
                      Layout{"binary", 1, false, false, false, false, true, false, 0},
                      Layout{"binary_zlib", 1, false, true, false, false, true, true, 0},
                      Layout{"binary_zlib_small_blocks_uint64", 1, false, true, true, false, true, false, 256},
                      Layout{"binary_uint64_bigendian", 1, false, false, true, true, false, true, 0},
                      Layout{"appended_raw", 2, false, false, false, false, true, false, 0},
                      Layout{"appended_raw_zlib_blocks", 2, false, true, false, false, true, true, 300},
                      Layout{"appended_base64", 2, true, false, false, false, true, false, 0},
                      Layout{"appended_base64_zlib_uint64_bigendian", 2, true, true, true, true, false, false, 512}),
    [](const ::testing::TestParamInfo<Layout>& i) { return std::string(i.param.name); });

// The file the application writes (appended, raw, zlib) reads back through the same reader.
TEST(VtpReader, ReadsItsOwnWriterAndTheBundledScapula) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1.0 / 3.0}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const fs::path file = scratch("own.vtp");
  writeMesh(mesh, file.string());
  const LoadedMesh m = readMesh(file.string(), ReadOptions{Units::Millimetres});
  EXPECT_EQ(m.mesh.vertices, mesh.vertices);
  EXPECT_EQ(m.mesh.triangles, mesh.triangles);
  const LoadedMesh s = readMesh(std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_opensim.vtp");
  EXPECT_EQ(s.mesh.vertices.size(), 770u);
  EXPECT_EQ(s.mesh.triangles.size(), 1543u);  // 1,541 polygons, two of them quads
}

const std::string kHead = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\"";

std::string piece(const std::string& pieceAttrs, const std::string& body) {
  return "<PolyData><Piece " + pieceAttrs + ">" + body + "</Piece></PolyData>";
}
const std::string kAsciiBody =
    "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>"
    "<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
    "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>";

// Float32 text is read to the nearest float, as VTK reads it (the bundled scapula's six-decimal coordinates are
// floats; read as doubles, its repaired derivative no longer matched, session 26).
TEST(VtpReader, AsciiFloat32IsReadAsFloats) {
  const fs::path file = scratch("float32.vtp");
  writeText(file, kHead + ">" + piece("NumberOfPoints=\"3\" NumberOfPolys=\"1\"",
      "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0.1 -0.113457 1e-50 1 0 0 0 1 0</DataArray></Points>"
      "<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
      "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>") + "</VTKFile>");
  const LoadedMesh m = readMesh(file.string(), ReadOptions{Units::Millimetres});
  EXPECT_EQ(m.mesh.vertices[0].x, double(0.1f));
  EXPECT_EQ(m.mesh.vertices[0].y, double(-0.113457f));
  EXPECT_EQ(m.mesh.vertices[0].z, 0.0);
}

// Each of these crashed (SIGSEGV, SIGFPE), hung or allocated gigabytes in VTK 9.1's reader. Now each is an
// InputError naming the file and the problem, read in milliseconds.
struct Bad {
  const char* name;
  std::string text;
  const char* message;
};

class VtpBadFiles : public ::testing::TestWithParam<Bad> {};

TEST_P(VtpBadFiles, AreInputErrors) {
  const Bad& b = GetParam();
  const fs::path file = scratch(std::string(b.name) + ".vtp");
  writeText(file, b.text);
  try {
    (void)readMesh(file.string());
    FAIL() << "no error for " << b.name;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(b.message), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, VtpBadFiles,
    ::testing::Values(
        Bad{"good_control_is_not_here", "", "file is empty"},
        Bad{"negative_points", kHead + ">" + piece("NumberOfPoints=\"-1\" NumberOfPolys=\"1\"", kAsciiBody) + "</VTKFile>",
            "NumberOfPoints = \"-1\" is not a non-negative integer"},
        Bad{"single_quoted_huge_points", kHead + ">" + piece("NumberOfPoints = '999999999999' NumberOfPolys=\"1\"", kAsciiBody) + "</VTKFile>",
            "NumberOfPoints = 999999999999, more than its size"},
        Bad{"entity_huge_points", kHead + ">" + piece("NumberOfPoints=\"&#57;99999999999\" NumberOfPolys=\"1\"", kAsciiBody) + "</VTKFile>",
            "NumberOfPoints = 999999999999, more than its size"},
        Bad{"huge_components", kHead + ">" + piece("NumberOfPoints=\"3\" NumberOfPolys=\"1\"",
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"4294967295\" format=\"ascii\">0 0 0</DataArray></Points>") + "</VTKFile>",
            "NumberOfComponents=\"3\""},
        Bad{"points_count_lies", kHead + ">" + piece("NumberOfPoints=\"4\" NumberOfPolys=\"1\"", kAsciiBody) + "</VTKFile>",
            "the Points array holds 9 values, the file declares 12"},
        Bad{"offsets_past_connectivity", kHead + ">" + piece("NumberOfPoints=\"3\" NumberOfPolys=\"1\"",
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>"
            "<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
            "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">100000000000</DataArray></Polys>") + "</VTKFile>",
            "Polys offsets are invalid at cell 0"},
        Bad{"binary_size_lies", kHead + ">" + piece("NumberOfPoints=\"1\" NumberOfPolys=\"0\"",
            // header says 0x7fffffff bytes; 12 bytes follow
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">/////w==AAAAAAAAAAAAAAAA</DataArray></Points>") + "</VTKFile>",
            "more than the file holds"},
        Bad{"zlib_block_size_zero", kHead + " compressor=\"vtkZLibDataCompressor\">" + piece("NumberOfPoints=\"1\" NumberOfPolys=\"0\"",
            // nblocks 1, block size 0, last 0, compressed size 4
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">AQAAAAAAAAAAAAAABAAAAA==AAAAAA==</DataArray></Points>") + "</VTKFile>",
            "invalid compression header"},
        Bad{"zlib_block_count_huge", kHead + " compressor=\"vtkZLibDataCompressor\">" + piece("NumberOfPoints=\"1\" NumberOfPolys=\"0\"",
            // nblocks 0xfffffff0
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">8P///wAQAAAAAAAA</DataArray></Points>") + "</VTKFile>",
            "compressed blocks, more than the file can hold"},
        Bad{"appended_offset_beyond", kHead + ">" + piece("NumberOfPoints=\"1\" NumberOfPolys=\"0\"",
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" offset=\"152\"/></Points>") +
            "<AppendedData encoding=\"raw\">_0123456789abcdef</AppendedData></VTKFile>",
            "beyond the"},
        Bad{"appended_offset_not_a_number", kHead + ">" + piece("NumberOfPoints=\"1\" NumberOfPolys=\"0\"",
            "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" offset=\"1.5e\"/></Points>") +
            "<AppendedData encoding=\"raw\">_xxxx</AppendedData></VTKFile>",
            "invalid offset \"1.5e\""},
        Bad{"truncated_inside_points", kHead + ">" + "<PolyData><Piece NumberOfPoints=\"3\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0",
            "(file truncated?)"},
        Bad{"lzma_compressor", kHead + " compressor=\"vtkLZMADataCompressor\">" + piece("NumberOfPoints=\"3\" NumberOfPolys=\"1\"", kAsciiBody) + "</VTKFile>",
            "is not supported (only vtkZLibDataCompressor)"},
        Bad{"two_pieces", kHead + "><PolyData><Piece NumberOfPoints=\"0\"/><Piece NumberOfPoints=\"0\"/></PolyData></VTKFile>",
            "only single-piece files are read"}),
    [](const ::testing::TestParamInfo<Bad>& i) { return std::string(i.param.name); });

}  // namespace
