// nscd/io/vtk_writer.cpp — see vtk_writer.hpp; the arrays are documented in docs/output.md.
//
// Format choice: vtkXMLPolyDataWriter in binary *appended* mode with raw (not base64) appended
// data, zlib-compressed, 64-bit block headers. This is VTK's default layout and the most compact
// one ParaView reads. VTK serializes each dataset into a string; this file then writes that
// string itself, so that I/O errors become nscd::Error (with the path) instead of messages on
// VTK's output window, and so that every file appears atomically (temporary file + rename).
#include "nscd/io/vtk_writer.hpp"

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <locale>
#include <sstream>
#include <system_error>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>

#include "nscd/core/error.hpp"
#include "nscd/core/registry.hpp"

namespace nscd {
namespace {

namespace fs = std::filesystem;

// ---- small file helpers ---------------------------------------------------------------

/// Writes `content` to `path` through `path.tmp` renamed over `path`: a reader (or a run killed
/// mid-write) never sees a half-written file.
void write_file_atomically(const fs::path& path, const std::string& content) {
  fs::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("VtkWriter: cannot open '" + tmp.string() + "' for writing: " + std::strerror(errno));
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) {
      std::error_code ignore;
      fs::remove(tmp, ignore);
      throw Error("VtkWriter: failed writing '" + tmp.string() + "' (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignore;
    fs::remove(tmp, ignore);
    throw Error("VtkWriter: cannot rename '" + tmp.string() + "' to '" + path.string() + "': " + ec.message());
  }
}

/// Escapes the five XML special characters (file names come from a user-chosen prefix).
std::string xml_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += ch;
    }
  }
  return out;
}

// ---- VTK arrays -------------------------------------------------------------------------

vtkSmartPointer<vtkIntArray> int_array(const char* name, vtkIdType n) {
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(1);
  a->SetNumberOfTuples(n);
  return a;
}

vtkSmartPointer<vtkDoubleArray> double_array(const char* name, int components, vtkIdType n) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(n);
  return a;
}

/// Stores a 2D vector as a 3-component tuple (x, y, 0): ParaView's glyphs and colouring by
/// magnitude expect 3 components.
void set_vec(vtkDoubleArray* a, vtkIdType i, Vec2 v) {
  const double t[3] = {v.x, v.y, 0.0};
  a->SetTypedTuple(i, t);
}

// ---- the two datasets ---------------------------------------------------------------------

/// One polygon cell per POLYG contactor, vertices in world coordinates; cell data from the
/// contactor's body.
vtkSmartPointer<vtkPolyData> bodies_dataset(const Registry& reg) {
  const PolygTable& t = reg.polyg;
  const BodyTable& b = reg.bodies;
  const auto n = static_cast<vtkIdType>(t.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(t.vertex.size()));
  vtkNew<vtkCellArray> polys;

  auto body_id = int_array("body_id", n), polyg_id = int_array("polyg_id", n);
  auto material = int_array("material", n), fixed = int_array("fixed", n);
  auto velocity = double_array("velocity", 3, n), displacement = double_array("displacement", 3, n);
  auto spin = double_array("spin", 1, n), rotation = double_array("rotation", 1, n);

  std::vector<vtkIdType> ids;
  for (std::size_t p = 0; p < t.size(); ++p) {
    const std::size_t i = t.body[p].index();
    // world vertex = centre of mass + R(angle) · body-frame vertex
    const Rot2 r = Rot2::of(b.angle[i]);
    const Vec2 g{b.x[i], b.y[i]};
    ids.clear();
    for (std::uint32_t k = t.first_vertex[p], e = k + t.vertex_count[p]; k < e; ++k) {
      const Vec2 w = g + r.apply(t.vertex[k]);
      points->SetPoint(static_cast<vtkIdType>(k), w.x, w.y, 0.0);
      ids.push_back(static_cast<vtkIdType>(k));
    }
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());

    const auto c = static_cast<vtkIdType>(p);
    body_id->SetValue(c, static_cast<int>(i));
    polyg_id->SetValue(c, static_cast<int>(p));
    material->SetValue(c, b.material[i].valid() ? static_cast<int>(b.material[i].index()) : -1);
    fixed->SetValue(c, b.inv_mass_x[i] == 0.0 && b.inv_mass_y[i] == 0.0 && b.inv_inertia[i] == 0.0 ? 1 : 0);
    set_vec(velocity, c, {b.vx[i], b.vy[i]});
    spin->SetValue(c, b.spin[i]);
    set_vec(displacement, c, {b.x[i] - b.x0[i], b.y[i] - b.y0[i]});
    rotation->SetValue(c, b.angle[i] - b.angle0[i]);
  }

  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  vtkCellData* cd = pd->GetCellData();
  for (vtkDataArray* a : {static_cast<vtkDataArray*>(body_id), static_cast<vtkDataArray*>(polyg_id),
                          static_cast<vtkDataArray*>(material), static_cast<vtkDataArray*>(velocity),
                          static_cast<vtkDataArray*>(spin), static_cast<vtkDataArray*>(displacement),
                          static_cast<vtkDataArray*>(rotation), static_cast<vtkDataArray*>(fixed)})
    cd->AddArray(a);
  return pd;
}

/// One line cell per PLPLx contact point: from the candidate's centre of mass to the
/// antagonist's, or to the contact point when the antagonist POLYG is big (a wall's centre of
/// mass may lie far from the contact, and the segment would cross the whole sample).
vtkSmartPointer<vtkPolyData> contacts_dataset(const Registry& reg) {
  const PlplxTable& c = reg.plplx;
  const BodyTable& b = reg.bodies;
  const std::size_t m = c.size();
  if (c.an_body.size() != m || c.cd_body.size() != m || c.normal.size() != m || c.point.size() != m ||
      c.gap.size() != m || c.rn.size() != m || c.rt.size() != m || c.status.size() != m)
    throw Error("VtkWriter: the PLPLx contact table has arrays of different lengths");
  const auto n = static_cast<vtkIdType>(m);

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * n);
  vtkNew<vtkCellArray> lines;

  auto normal = double_array("normal", 3, n), force = double_array("force", 3, n);
  auto point = double_array("point", 3, n);
  auto rn = double_array("rn", 1, n), rt = double_array("rt", 1, n), gap = double_array("gap", 1, n);
  auto status = int_array("status", n);
  auto candidate_body = int_array("candidate_body", n), antagonist_body = int_array("antagonist_body", n);

  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t bc = c.cd_body[k].index(), ba = c.an_body[k].index();
    const Vec2 from{b.x[bc], b.y[bc]};
    const Vec2 to = reg.polyg.is_big[c.antagonist[k].index()] ? c.point[k] : Vec2{b.x[ba], b.y[ba]};
    const auto i = static_cast<vtkIdType>(k);
    points->SetPoint(2 * i, from.x, from.y, 0.0);
    points->SetPoint(2 * i + 1, to.x, to.y, 0.0);
    const vtkIdType seg[2] = {2 * i, 2 * i + 1};
    lines->InsertNextCell(2, seg);

    // Force on the candidate in world components: R = rn n + rt t, with t = perp(n).
    const Vec2 nn = c.normal[k];
    set_vec(normal, i, nn);
    rn->SetValue(i, c.rn[k]);
    rt->SetValue(i, c.rt[k]);
    set_vec(force, i, c.rn[k] * nn + c.rt[k] * perp(nn));
    gap->SetValue(i, c.gap[k]);
    status->SetValue(i, static_cast<int>(c.status[k]));
    set_vec(point, i, c.point[k]);
    candidate_body->SetValue(i, static_cast<int>(bc));
    antagonist_body->SetValue(i, static_cast<int>(ba));
  }

  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  vtkCellData* cd = pd->GetCellData();
  for (vtkDataArray* a : {static_cast<vtkDataArray*>(normal), static_cast<vtkDataArray*>(rn),
                          static_cast<vtkDataArray*>(rt), static_cast<vtkDataArray*>(force),
                          static_cast<vtkDataArray*>(gap), static_cast<vtkDataArray*>(status),
                          static_cast<vtkDataArray*>(point), static_cast<vtkDataArray*>(candidate_body),
                          static_cast<vtkDataArray*>(antagonist_body)})
    cd->AddArray(a);
  return pd;
}

/// Serializes a dataset as a .vtp document (binary appended, raw, zlib) and writes it.
void write_vtp(vtkPolyData* pd, const fs::path& path) {
  vtkNew<vtkXMLPolyDataWriter> w;
  w->SetInputData(pd);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  w->SetCompressorTypeToZLib();
  w->SetHeaderTypeToUInt64();
  w->WriteToOutputStringOn();
  if (w->Write() != 1) throw Error("VtkWriter: VTK failed to serialize '" + path.string() + "'");
  write_file_atomically(path, w->GetOutputString());
}

}  // namespace

VtkWriter::VtkWriter(std::filesystem::path dir, std::string prefix) : dir_(std::move(dir)), prefix_(std::move(prefix)) {
  if (dir_.empty()) throw Error("VtkWriter: the output directory path is empty");
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw Error("VtkWriter: cannot create output directory '" + dir_.string() + "': " + ec.message());
  if (!fs::is_directory(dir_, ec))
    throw Error("VtkWriter: output path '" + dir_.string() + "' exists and is not a directory");
}

void VtkWriter::add_to_collection(Collection& c, double time, const std::string& file) {
  c.entries.emplace_back(time, file);
  std::ostringstream s;
  s.imbue(std::locale::classic());  // a '.' decimal separator whatever the user's locale
  s << std::setprecision(17);       // 17 significant digits: the time round-trips exactly
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\""
    << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian") << "\">\n"
    << "  <Collection>\n";
  for (const auto& [t, f] : c.entries)
    s << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << xml_escape(f) << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(dir_ / (prefix_ + c.name + ".pvd"), s.str());
}

void VtkWriter::write_frame(const Registry& reg, const VtkFrameOptions& opts) {
  // The number is taken before writing: a frame that throws half-way still uses up its number,
  // so the next frame never overwrites a file a collection already lists.
  const int frame = frames_++;
  char number[16];
  std::snprintf(number, sizeof number, "_%06d.vtp", frame);
  if (opts.bodies) {
    const std::string file = prefix_ + bodies_.name + number;
    write_vtp(bodies_dataset(reg), dir_ / file);
    add_to_collection(bodies_, reg.time, file);
  }
  if (opts.contacts) {
    const std::string file = prefix_ + contacts_.name + number;
    write_vtp(contacts_dataset(reg), dir_ / file);
    add_to_collection(contacts_, reg.time, file);
  }
}

}  // namespace nscd
