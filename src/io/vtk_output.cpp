#include "mfree/io/vtk_output.hpp"

#include <fmt/format.h>
#include <unistd.h>
#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <set>
#include <system_error>

#include "mfree/core/error.hpp"
#include "mfree/io/atomic_file.hpp"

namespace mfree {

namespace {

/// Takes the messages VTK objects report through ErrorEvent. With an observer attached, VTK
/// hands the message to it instead of printing it, so failures reach the caller as one mfree
/// error and stderr stays quiet.
class ErrorCollector : public vtkCommand {
 public:
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long event, void* call_data) override {
    if (event != vtkCommand::ErrorEvent) return;
    if (message.empty() && call_data != nullptr) message = static_cast<const char*>(call_data);
    failed = true;
  }
  bool failed = false;
  std::string message;
};

/// The message proper of a VTK error report, which reads
///   "ERROR: In <source file>, line <n>\n<class> (<address>): <message>\n\n".
std::string tidy(const std::string& report) {
  std::string message = report;
  if (const auto line = message.find('\n'); line != std::string::npos) message.erase(0, line + 1);
  if (const auto colon = message.find("): "); colon != std::string::npos) message.erase(0, colon + 3);
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back())))
    message.pop_back();
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message;
}

/// Checks points and fields before any file is touched.
void validate(const std::filesystem::path& path, const std::vector<Vec2>& points,
              const std::vector<PointField>& fields) {
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) {
      throw NumericalError(fmt::format("{}: point coordinates are not finite at point {} "
                                       "(({}, {})); nothing was written",
                                       path.string(), i, points[i].x(), points[i].y()));
    }
  }
  std::set<std::string> names;
  for (const PointField& f : fields) {
    if (f.name.empty())
      throw InputError(fmt::format("{}: a point field has an empty name", path.string()));
    if (!names.insert(f.name).second)
      throw InputError(fmt::format("{}: two point fields are named '{}'", path.string(), f.name));
    if (f.components < 1) {
      throw InputError(fmt::format("{}: field '{}' has {} components; it needs at least 1",
                                   path.string(), f.name, f.components));
    }
    const std::size_t expected = static_cast<std::size_t>(f.components) * n;
    if (f.values.size() != expected) {
      throw InputError(fmt::format(
          "{}: field '{}' has {} values; {} points x {} components need {}", path.string(),
          f.name, f.values.size(), n, f.components, expected));
    }
    const auto bad = std::find_if(f.values.begin(), f.values.end(),
                                  [](double v) { return !std::isfinite(v); });
    if (bad != f.values.end()) {
      const auto k = static_cast<std::size_t>(bad - f.values.begin());
      throw NumericalError(fmt::format(
          "{}: field '{}' is not finite at point {} (component {} is {}); nothing was written",
          path.string(), f.name, k / static_cast<std::size_t>(f.components),
          k % static_cast<std::size_t>(f.components), *bad));
    }
  }
}

/// The point-data array for one field (2D vectors padded with z = 0, see the header).
vtkSmartPointer<vtkDoubleArray> make_array(const PointField& f, std::size_t n) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(f.name.c_str());
  const int written = f.components == 2 ? 3 : f.components;
  array->SetNumberOfComponents(written);
  array->SetNumberOfTuples(static_cast<vtkIdType>(n));
  double* out = array->GetPointer(0);
  if (f.components == 2) {
    for (std::size_t i = 0; i < n; ++i) {
      out[3 * i] = f.values[2 * i];
      out[3 * i + 1] = f.values[2 * i + 1];
      out[3 * i + 2] = 0.0;
    }
  } else {
    std::copy(f.values.begin(), f.values.end(), out);
  }
  if (f.components == 3) {
    array->SetComponentName(0, "xx");
    array->SetComponentName(1, "yy");
    array->SetComponentName(2, "xy");
  }
  return array;
}

/// The grid of the points (z = 0) and fields; cells are added by the caller.
vtkSmartPointer<vtkUnstructuredGrid> make_grid(const std::vector<Vec2>& points,
                                               const std::vector<PointField>& fields) {
  const std::size_t n = points.size();
  vtkNew<vtkDoubleArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(static_cast<vtkIdType>(n));
  double* out = xyz->GetPointer(0);
  for (std::size_t i = 0; i < n; ++i) {
    out[3 * i] = points[i].x();
    out[3 * i + 1] = points[i].y();
    out[3 * i + 2] = 0.0;
  }
  vtkNew<vtkPoints> vtk_points;
  vtk_points->SetData(xyz);

  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(vtk_points);
  for (const PointField& f : fields) grid->GetPointData()->AddArray(make_array(f, n));
  return grid;
}

/// Gives the grid `count` cells of one type with `size` points each; connectivity(c, k) is
/// the k-th point of cell c.
template <class Connectivity>
void set_cells(vtkUnstructuredGrid& grid, std::size_t count, int size, unsigned char type,
               Connectivity connectivity) {
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(count + 1));
  vtkNew<vtkIdTypeArray> ids;
  ids->SetNumberOfValues(static_cast<vtkIdType>(count * static_cast<std::size_t>(size)));
  vtkIdType* off = offsets->GetPointer(0);
  vtkIdType* id = ids->GetPointer(0);
  for (std::size_t c = 0; c < count; ++c) {
    off[c] = static_cast<vtkIdType>(c) * size;
    for (int k = 0; k < size; ++k) id[c * static_cast<std::size_t>(size) + k] = connectivity(c, k);
  }
  off[count] = static_cast<vtkIdType>(count) * size;
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, ids);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfValues(static_cast<vtkIdType>(count));
  std::fill_n(types->GetPointer(0), count, type);
  grid.SetCells(types, cells);
}

/// Writes the grid to a temporary file beside `path` and renames it into place.
void write_grid(const std::filesystem::path& path, vtkUnstructuredGrid& grid) {
  std::error_code ec;
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) {
      throw Error(fmt::format("cannot create folder {} for {}: {}", path.parent_path().string(),
                              path.string(), ec.message()));
    }
  }
  const std::filesystem::path tmp = path.string() + fmt::format(".tmp{}.vtu", ::getpid());

  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  vtkNew<ErrorCollector> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(&grid);
  // Raw binary after the XML header (no base64): the smallest and fastest form ParaView reads.
  // 64-bit block headers let a single array exceed 4 GiB. LZ4 rather than VTK's default zlib:
  // on 10^6 points with three fields it writes 13x faster (0.4 s against 5.5 s) for files
  // 20% larger, as field values compress poorly either way.
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetHeaderTypeToUInt64();
  writer->SetCompressorTypeToLZ4();
  const int ok = writer->Write();
  if (ok != 1 || errors->failed) {
    std::filesystem::remove(tmp, ec);
    throw Error(fmt::format("cannot write {}: {}", path.string(),
                            errors->message.empty() ? std::string("VTK's writer failed")
                                                    : tidy(errors->message)));
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    std::filesystem::remove(tmp, ec);
    throw Error(fmt::format("cannot move {} into place: {}", path.string(), why));
  }
}

/// `text` with the five XML special characters escaped, for an attribute value.
std::string xml_escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

void write_point_cloud_vtu(const std::filesystem::path& path, const std::vector<Vec2>& points,
                           const std::vector<PointField>& fields) {
  validate(path, points, fields);
  const auto grid = make_grid(points, fields);
  set_cells(*grid, points.size(), 1, VTK_VERTEX,
            [](std::size_t c, int) { return static_cast<vtkIdType>(c); });
  write_grid(path, *grid);
}

void write_triangles_vtu(const std::filesystem::path& path, const std::vector<Vec2>& points,
                         const std::vector<std::array<Index, 3>>& triangles,
                         const std::vector<PointField>& fields) {
  validate(path, points, fields);
  const auto n = static_cast<std::size_t>(points.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const Index v : triangles[t]) {
      if (v < 0 || static_cast<std::size_t>(v) >= n) {
        throw InputError(fmt::format("{}: triangle {} refers to point {}, but there are {} points",
                                     path.string(), t, v, n));
      }
    }
  }
  const auto grid = make_grid(points, fields);
  set_cells(*grid, triangles.size(), 3, VTK_TRIANGLE, [&](std::size_t c, int k) {
    return static_cast<vtkIdType>(triangles[c][static_cast<std::size_t>(k)]);
  });
  write_grid(path, *grid);
}

void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& steps) {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (std::size_t s = 0; s < steps.size(); ++s) {
    const auto& [time, file] = steps[s];
    if (!std::isfinite(time)) {
      throw NumericalError(
          fmt::format("{}: time of step {} ('{}') is {}", path.string(), s, file, time));
    }
    if (file.empty())
      throw InputError(fmt::format("{}: step {} has an empty file name", path.string(), s));
    // "{}" prints the shortest text that reads back to the same double.
    text += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time,
                        xml_escaped(file));
  }
  text +=
      "  </Collection>\n"
      "</VTKFile>\n";
  write_file_atomically(path, text);
}

VtuContents read_vtu(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(
        fmt::format("VTK file '{}' does not exist or is not a regular file", path.string()));
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  vtkNew<ErrorCollector> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  // The reader's internal XML parser and array reader report through their own observers.
  reader->SetParserErrorObserver(errors);
  reader->SetReaderErrorObserver(errors);
  if (reader->CanReadFile(path.c_str()) == 0) {
    throw InputError(fmt::format("'{}' is not a VTK XML unstructured grid (.vtu) file",
                                 path.string()));
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (errors->failed || grid == nullptr) {
    throw InputError(fmt::format("cannot read '{}': {}", path.string(),
                                 errors->message.empty() ? std::string("VTK's reader failed")
                                                         : tidy(errors->message)));
  }

  VtuContents out;
  const vtkIdType n = grid->GetNumberOfPoints();
  out.points.reserve(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    double x[3];
    grid->GetPoint(i, x);
    out.points.emplace_back(x[0], x[1]);
  }
  vtkPointData* data = grid->GetPointData();
  for (int a = 0; a < data->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = data->GetArray(a);  // null for string and other non-numeric arrays
    if (array == nullptr) continue;
    const std::string name = array->GetName() != nullptr ? array->GetName() : "";
    const int components = array->GetNumberOfComponents();
    std::vector<double> values(static_cast<std::size_t>(array->GetNumberOfTuples()) *
                               static_cast<std::size_t>(components));
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      array->GetTuple(t, values.data() + static_cast<std::size_t>(t) * components);
    out.array_names.push_back(name);
    out.arrays[name] = std::move(values);
    out.components[name] = components;
  }
  out.cells = static_cast<Index>(grid->GetNumberOfCells());
  return out;
}

}  // namespace mfree
