// nscd/io/vtk_writer.cpp — see vtk_writer.hpp; the arrays are documented in docs/output.md.
//
// Format choice: vtkXMLPolyDataWriter in binary *appended* mode with raw (not base64) appended
// data, zlib-compressed, 64-bit block headers. This is VTK's default layout and the most compact
// one ParaView reads. VTK serializes each dataset into a string; this file then writes that
// string itself, so that I/O errors become nscd::Error (with the path) instead of messages on
// VTK's output window, and so that every file appears atomically (temporary file + rename).
// resume() reads the .pvd collections back with VTK's XML parser (ParaView's own), its error
// messages captured into the nscd::Error.
#include "nscd/io/vtk_writer.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <locale>
#include <sstream>
#include <string_view>
#include <system_error>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataWriter.h>

#include "nscd/contactors/pt2dx.hpp"
#include "nscd/interactions/interaction_table.hpp"
#include "nscd/interactions/round_detection.hpp"
#include "nscd/io/atomic_file.hpp"
#include "nscd/contactors/contactor_row.hpp"
#include "nscd/core/error.hpp"
#include "nscd/registry/registry.hpp"

namespace nscd {
namespace {

namespace fs = std::filesystem;

// ---- small file helpers ---------------------------------------------------------------

/// Every file appears whole (nscd::atomic_write): a reader (or a run killed mid-write) never
/// sees a half-written file.
void write_file_atomically(const fs::path& path, const std::string& content) { atomic_write(path, content); }

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

/// Attaches the arrays to the dataset's cell data, in this order.
void add_cell_arrays(vtkPolyData* pd, std::initializer_list<vtkDataArray*> arrays) {
  for (vtkDataArray* a : arrays) pd->GetCellData()->AddArray(a);
}

/// Stores a 2D vector as a 3-component tuple (x, y, 0): ParaView's glyphs and colouring by
/// magnitude expect 3 components.
void set_vec(vtkDoubleArray* a, vtkIdType i, Vec2 v) {
  const double t[3] = {v.x, v.y, 0.0};
  a->SetTypedTuple(i, t);
}

// ---- the three datasets ---------------------------------------------------------------------

/// The cells of every contactor that its kind's row draws (contactor_row.hpp: POLYG, DISKx, JONCx,
/// xKSID and a scene's added kinds), kind after kind, each in the body frame, with its body and
/// kind: a POLYG is its polygon, a DISKx a 32-gon, a JONCx its outline, an xKSID ring a band of
/// 64 quadrilaterals outside its hole (a filled cell would hide the drum's content).
struct Cells {
  KindOutline outline;
  std::vector<std::uint32_t> body;
  std::vector<int> polyg, kind;
};

Cells drawn_cells(const Registry& reg) {
  Cells c;
  for (std::size_t k = 0; k < kind_count(reg); ++k) {
    const ContactorKindRow& row = *kind_row(reg, static_cast<std::uint8_t>(k));
    if (row.draw == nullptr) continue;
    for (std::uint32_t i = 0, n = static_cast<std::uint32_t>(row.count(reg)); i < n; ++i) {
      row.draw(reg, i, c.outline);
      c.body.resize(c.outline.cell_end.size(), row.body(reg, i).value);
      c.polyg.resize(c.outline.cell_end.size(), k == 0 ? static_cast<int>(i) : -1);
      c.kind.resize(c.outline.cell_end.size(), static_cast<int>(k));
    }
  }
  return c;
}

/// One polygon cell per contactor cell (drawn_cells), vertices in world coordinates; cell data
/// from the contactor's body. A scene with other kinds than POLYG also gets `contactor_kind`
/// (0 POLYG, 1 DISKx, 2 JONCx, 3 xKSID, then the added kinds' numbers).
vtkSmartPointer<vtkPolyData> bodies_dataset(const Registry& reg) {
  const BodyTable& b = reg.bodies;
  const bool round = has_round_contactors(reg);
  const Cells cells = drawn_cells(reg);
  const auto n = static_cast<vtkIdType>(cells.body.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;

  auto body_id = int_array("body_id", n), polyg_id = int_array("polyg_id", n);
  auto material = int_array("material", n), fixed = int_array("fixed", n), kind = int_array("contactor_kind", n);
  auto velocity = double_array("velocity", 3, n), displacement = double_array("displacement", 3, n);
  auto spin = double_array("spin", 1, n), rotation = double_array("rotation", 1, n);

  std::vector<vtkIdType> ids;
  std::size_t first = 0;
  for (vtkIdType c = 0; c < n; ++c) {
    const std::size_t i = cells.body[static_cast<std::size_t>(c)],
                      end = cells.outline.cell_end[static_cast<std::size_t>(c)];
    const Rot2 r = Rot2::of(b.angle[i]);
    const Vec2 g{b.x[i], b.y[i]};
    ids.clear();
    for (std::size_t v = first; v < end; ++v) {  // world vertex = centre of mass + R(angle) · body-frame vertex
      const Vec2 w = g + r.apply(cells.outline.points[v]);
      ids.push_back(points->InsertNextPoint(w.x, w.y, 0.0));
    }
    first = end;
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    body_id->SetValue(c, static_cast<int>(i));
    polyg_id->SetValue(c, cells.polyg[static_cast<std::size_t>(c)]);
    kind->SetValue(c, cells.kind[static_cast<std::size_t>(c)]);
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
  if (round)
    add_cell_arrays(pd, {body_id, polyg_id, kind, material, velocity, spin, displacement, rotation, fixed});
  else
    add_cell_arrays(pd, {body_id, polyg_id, material, velocity, spin, displacement, rotation, fixed});
  return pd;
}

/// One line cell per contact point (every interaction kind): from the candidate's centre of mass
/// to the antagonist's, or to the contact point when the antagonist is a wall (a big POLYG, a
/// JONCx, an xKSID, an added kind). A scene with round contactors also gets `interaction` (the line of the
/// interaction table, named by the field data `interaction_names`). A wall's centre of mass may
/// lie far from the contact, and the segment would cross the whole sample.
vtkSmartPointer<vtkPolyData> contacts_dataset(const Registry& reg) {
  const ContactTable& c = reg.contacts;
  const BodyTable& b = reg.bodies;
  const std::size_t m = c.size();
  if (c.an_body.size() != m || c.cd_body.size() != m || c.normal.size() != m || c.point.size() != m ||
      c.gap.size() != m || c.rn.size() != m || c.rt.size() != m || c.status.size() != m)
    throw Error("VtkWriter: the contact table has arrays of different lengths");
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
  auto interaction = int_array("interaction", n);
  const bool round = has_round_contactors(reg);

  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t bc = c.cd_body[k].index(), ba = c.an_body[k].index();
    const Vec2 from{b.x[bc], b.y[bc]};
    const ContactorId an = c.antagonist[k];
    const std::uint8_t an_kind = contactor_kind_bits(an);  // a JONCx, an xKSID or an added kind is a wall
    const bool wall = an_kind == 0 ? reg.polyg.is_big[contactor_index(an)] != 0 : an_kind != 1;
    const Vec2 to = wall ? c.point[k] : Vec2{b.x[ba], b.y[ba]};
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
    if (round) interaction->SetValue(i, interaction_number(reg, interaction_of(c.candidate[k], an)));
  }

  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  if (!round) {  // a polygon scene's file is that of a polygon-only code
    add_cell_arrays(pd, {normal, rn, rt, force, gap, status, point, candidate_body, antagonist_body});
    return pd;
  }
  add_cell_arrays(pd, {normal, rn, rt, force, gap, status, point, candidate_body, antagonist_body, interaction});
  // the numbers' names, in the file itself (field data, shown by ParaView's spreadsheet view)
  vtkNew<vtkStringArray> names;
  names->SetName("interaction_names");
  for (const std::string_view s : interaction_names(reg)) names->InsertNextValue(std::string(s));
  pd->GetFieldData()->AddArray(names);
  return pd;
}

/// One line cell per PTPT2 link, from the antagonist point to the candidate point at the
/// current configuration (reg.bodies x, y, angle), so the segment points along the link's
/// normal n. The length and strain are recomputed from that configuration; rn is the force of
/// the last solve as stored in the table.
vtkSmartPointer<vtkPolyData> springs_dataset(const Registry& reg) {
  const Ptpt2Table& l = reg.links;
  const BodyTable& b = reg.bodies;
  const std::size_t m = l.size();
  if (l.antagonist.size() != m || l.law.size() != m || l.rn.size() != m)
    throw Error("VtkWriter: the PTPT2 link table has arrays of different lengths");
  if (reg.points.point.size() != reg.points.size())
    throw Error("VtkWriter: the PT2Dx point table has arrays of different lengths");
  const auto n = static_cast<vtkIdType>(m);

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * n);
  vtkNew<vtkCellArray> lines;
  auto rn = double_array("rn", 1, n), length = double_array("length", 1, n), strain = double_array("strain", 1, n);
  auto k_arr = double_array("k", 1, n), nu = double_array("nu", 1, n);
  auto link_id = int_array("link_id", n);

  // world position of a link's end point; an id that leads nowhere is an error, not a crash
  auto end_point = [&](PointId p, std::size_t link) {
    if (!p.valid() || p.index() >= reg.points.size() || reg.points.body[p.index()].index() >= b.size())
      throw Error("VtkWriter: PTPT2 link " + std::to_string(link) + " refers to an unknown point or body");
    const std::size_t i = reg.points.body[p.index()].index();
    return point_position(reg, p, b.x[i], b.y[i], b.angle[i]);
  };

  for (std::size_t j = 0; j < m; ++j) {
    const Vec2 pa = end_point(l.antagonist[j], j), pc = end_point(l.candidate[j], j);
    const auto i = static_cast<vtkIdType>(j);
    points->SetPoint(2 * i, pa.x, pa.y, 0.0);
    points->SetPoint(2 * i + 1, pc.x, pc.y, 0.0);
    const vtkIdType seg[2] = {2 * i, 2 * i + 1};
    lines->InsertNextCell(2, seg);

    // VOIGT_ROD strain ε = (L − L0)/L0 − ε0 (registry.hpp), at the current length L
    const VoigtRod& law = l.law[j];
    const double len = norm(pc - pa);
    rn->SetValue(i, l.rn[j]);
    length->SetValue(i, len);
    strain->SetValue(i, (len - law.L0) / law.L0 - law.eps0);
    k_arr->SetValue(i, law.k);
    nu->SetValue(i, law.nu);
    link_id->SetValue(i, static_cast<int>(j));
  }

  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  add_cell_arrays(pd, {rn, length, strain, k_arr, nu, link_id});
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

// ---- reading a .pvd back (resume) --------------------------------------------------------

using Entries = std::vector<std::pair<double, std::string>>;

[[noreturn]] void malformed(const fs::path& pvd, const std::string& why) {
  throw Error("VtkWriter: malformed collection '" + pvd.string() + "': " + why);
}

/// Collects the messages VTK would print on its output window (an ErrorEvent observer on the
/// object replaces the printing), so that they go into the nscd::Error instead.
void keep_vtk_message(vtkObject*, unsigned long, void* client, void* call) {
  std::string msg = call ? static_cast<const char*>(call) : "";
  // "ERROR: In <source>, line N\n<class> (0x...): <what>\n\n": keep <what>
  if (const std::size_t p = msg.find("): ", msg.find('\n')); p != std::string::npos) msg.erase(0, p + 3);
  while (!msg.empty() && std::isspace(static_cast<unsigned char>(msg.back()))) msg.pop_back();
  auto* out = static_cast<std::string*>(client);
  if (out->empty()) *out = msg;
}

/// The (timestep, file) of every DataSet of a VTK collection document, parsed with VTK's XML
/// parser (the one ParaView reads .pvd files with).
Entries read_collection(const fs::path& pvd) {
  vtkNew<vtkXMLDataParser> parser;
  std::string vtk_error;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(keep_vtk_message);
  observer->SetClientData(&vtk_error);
  parser->AddObserver(vtkCommand::ErrorEvent, observer);
  parser->SetFileName(pvd.string().c_str());
  if (parser->Parse() != 1) malformed(pvd, vtk_error.empty() ? "not an XML document" : vtk_error);

  vtkXMLDataElement* root = parser->GetRootElement();
  const char* type = root ? root->GetAttribute("type") : nullptr;
  if (!root || std::strcmp(root->GetName(), "VTKFile") != 0 || !type || std::strcmp(type, "Collection") != 0)
    malformed(pvd, "the root element is not <VTKFile type=\"Collection\">");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (!collection) malformed(pvd, "no <Collection> element");

  Entries out;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* ds = collection->GetNestedElement(i);
    if (std::strcmp(ds->GetName(), "DataSet") != 0) continue;
    const char* time = ds->GetAttribute("timestep");
    const char* file = ds->GetAttribute("file");
    if (!time || !file) malformed(pvd, "a DataSet without a timestep or a file");
    // from_chars: locale-independent, and the whole attribute must be the number
    const std::string_view tv(time);
    double t = 0.0;
    const auto [end, ec] = std::from_chars(tv.data(), tv.data() + tv.size(), t);
    if (ec != std::errc() || end != tv.data() + tv.size() || !std::isfinite(t))
      malformed(pvd, "timestep \"" + std::string(tv) + "\" is not a finite number");
    out.emplace_back(t, file);
  }
  return out;
}

/// The frame number of `file` = "<stem>_<digits>.vtp" (stem = prefix + kind); -1 if it has
/// another form.
int frame_number(std::string_view file, const std::string& stem) {
  if (file.size() < stem.size() + 6 || !file.starts_with(stem) || file[stem.size()] != '_' || !file.ends_with(".vtp"))
    return -1;
  const std::string_view digits = file.substr(stem.size() + 1, file.size() - stem.size() - 5);
  unsigned n = 0;  // unsigned: from_chars then takes digits only, no sign
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  return ec == std::errc() && end == digits.data() + digits.size() && n <= INT_MAX ? static_cast<int>(n) : -1;
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
  write_collection(c);
}

void VtkWriter::write_collection(const Collection& c) const {
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
  write_file_atomically(pvd_path(c), s.str());
}

void VtkWriter::resume(double up_to_time) {
  if (std::isnan(up_to_time)) throw Error("VtkWriter::resume: the time is NaN");
  // Parse everything first: a malformed file leaves the writer and every file as they were.
  Collection* all[] = {&bodies_, &contacts_, &springs_};
  Entries kept[3];
  bool present[3] = {false, false, false};
  int last = -1;  // highest kept frame number over all kinds
  for (int i = 0; i < 3; ++i) {
    const fs::path pvd = pvd_path(*all[i]);
    std::error_code ec;
    present[i] = fs::exists(pvd, ec);
    if (ec) throw Error("VtkWriter: cannot inspect '" + pvd.string() + "': " + ec.message());
    if (!present[i]) continue;  // nothing of this kind to resume
    for (auto& [t, file] : read_collection(pvd)) {
      const int n = frame_number(file, prefix_ + all[i]->name);
      if (n < 0) malformed(pvd, "'" + file + "' is not a " + prefix_ + all[i]->name + "_NNNNNN.vtp frame");
      if (t > up_to_time) continue;  // a frame after the checkpoint: dropped, its number reused
      last = std::max(last, n);
      kept[i].emplace_back(t, std::move(file));
    }
  }
  for (int i = 0; i < 3; ++i) {
    all[i]->entries = std::move(kept[i]);
    if (present[i]) write_collection(*all[i]);
  }
  frames_ = last + 1;
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
  if (opts.springs && !reg.links.empty()) {
    const std::string file = prefix_ + springs_.name + number;
    write_vtp(springs_dataset(reg), dir_ / file);
    add_to_collection(springs_, reg.time, file);
  }
}

}  // namespace nscd
