#include "text_header.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include "palpate/core/error.hpp"
#include "voxel_data.hpp"

namespace palpate::volume {
namespace {

std::string trim(std::string text) {
  const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
  text.erase(text.begin(), std::find_if_not(text.begin(), text.end(), space));
  text.erase(std::find_if_not(text.rbegin(), text.rend(), space).base(), text.end());
  return text;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

std::vector<double> numbers(const std::string& text) {
  std::string spaced = text;
  for (char& c : spaced)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(spaced);
  std::vector<double> out;
  for (double value; in >> value;) out.push_back(value);
  return out;
}

struct Header {
  std::map<std::string, std::string> fields;  // keys lower-cased
  std::size_t data_offset = 0;                // where the voxels start, when in the same file
  const std::string* find(const std::string& key) const {
    const auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  }
};

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw Error(file, 0, what);
}

void check_size(const std::vector<double>& sizes, const std::filesystem::path& file) {
  if (sizes.size() != 3 ||
      std::any_of(sizes.begin(), sizes.end(), [](double s) { return s < 2 || s > 1e5; })) {
    fail(file, "not a volume palpate reads: " + std::to_string(sizes.size()) +
                   " sizes (3 of at least 2 voxels each are needed)");
  }
}

VoxelType nrrd_type(const std::string& name, const std::filesystem::path& file) {
  static const std::map<std::string, VoxelType> types = {{"signed char", VoxelType::int8},
                                                         {"int8", VoxelType::int8},
                                                         {"int8_t", VoxelType::int8},
                                                         {"uchar", VoxelType::uint8},
                                                         {"unsigned char", VoxelType::uint8},
                                                         {"uint8", VoxelType::uint8},
                                                         {"uint8_t", VoxelType::uint8},
                                                         {"short", VoxelType::int16},
                                                         {"short int", VoxelType::int16},
                                                         {"signed short", VoxelType::int16},
                                                         {"signed short int", VoxelType::int16},
                                                         {"int16", VoxelType::int16},
                                                         {"int16_t", VoxelType::int16},
                                                         {"ushort", VoxelType::uint16},
                                                         {"unsigned short", VoxelType::uint16},
                                                         {"unsigned short int", VoxelType::uint16},
                                                         {"uint16", VoxelType::uint16},
                                                         {"uint16_t", VoxelType::uint16},
                                                         {"int", VoxelType::int32},
                                                         {"signed int", VoxelType::int32},
                                                         {"int32", VoxelType::int32},
                                                         {"int32_t", VoxelType::int32},
                                                         {"uint", VoxelType::uint32},
                                                         {"unsigned int", VoxelType::uint32},
                                                         {"uint32", VoxelType::uint32},
                                                         {"uint32_t", VoxelType::uint32},
                                                         {"longlong", VoxelType::int64},
                                                         {"long long", VoxelType::int64},
                                                         {"int64", VoxelType::int64},
                                                         {"int64_t", VoxelType::int64},
                                                         {"ulonglong", VoxelType::uint64},
                                                         {"unsigned long long", VoxelType::uint64},
                                                         {"uint64", VoxelType::uint64},
                                                         {"uint64_t", VoxelType::uint64},
                                                         {"float", VoxelType::float32},
                                                         {"double", VoxelType::float64}};
  const auto it = types.find(lower(name));
  if (it == types.end()) fail(file, "unsupported data type '" + name + "' (integers or floats are read)");
  return it->second;
}

}  // namespace

Volume load_nrrd(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || !line.starts_with("NRRD000"))
    fail(file, "not a NRRD file (no NRRD000x magic line)");
  Header header;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;                                               // the voxels follow
    if (line[0] == '#' || line.find(":=") != std::string::npos) continue;  // comments, key/value pairs
    const auto colon = line.find(": ");
    if (colon == std::string::npos) fail(file, "not a NRRD field: '" + line + "'");
    header.fields[lower(trim(line.substr(0, colon)))] = trim(line.substr(colon + 2));
  }
  header.data_offset = std::size_t(in.tellg());
  const auto required = [&](const char* key) -> const std::string& {
    const std::string* value = header.find(key);
    if (!value) fail(file, std::string("the NRRD header has no '") + key + "' field");
    return *value;
  };
  if (numbers(required("dimension")) != std::vector<double>{3.0})
    fail(file,
         "not a volume palpate reads: dimension " + required("dimension") + " (3D scalar volumes only)");
  Volume volume;
  volume.source = file;
  const std::vector<double> sizes = numbers(required("sizes"));
  check_size(sizes, file);
  volume.size = {int(sizes[0]), int(sizes[1]), int(sizes[2])};

  VoxelData data;
  data.type = nrrd_type(required("type"), file);
  const std::string encoding = lower(required("encoding"));
  if (encoding == "gzip" || encoding == "gz") {
    data.gzip = true;
  } else if (encoding != "raw") {
    fail(file, "NRRD encoding '" + encoding + "' is not read (raw or gzip)");
  }
  if (const std::string* endian = header.find("endian")) data.big_endian = lower(*endian) == "big";
  for (const char* key : {"line skip", "byte skip"})
    if (const std::string* skip = header.find(key); skip && numbers(*skip) != std::vector<double>{0.0})
      fail(file, std::string("NRRD '") + key + "' is not read");
  const std::string* detached = header.find("data file");
  if (!detached) detached = header.find("datafile");
  if (detached) {
    if (detached->starts_with("LIST") || detached->find('%') != std::string::npos)
      fail(file, "NRRD data split over several files is not read");
    data.file = file.parent_path() / *detached;
  } else {
    data.file = file;
    data.offset = header.data_offset;
  }
  volume.values = read_voxels(
      data, std::size_t(volume.size.x) * std::size_t(volume.size.y) * std::size_t(volume.size.z), file);

  if (const std::string* directions = header.find("space directions")) {
    const std::vector<double> axes = numbers(*directions);
    if (axes.size() != 9) fail(file, "NRRD 'space directions' needs three 3D vectors: '" + *directions + "'");
    glm::dmat3 axes_world;
    for (int axis = 0; axis < 3; ++axis)
      axes_world[axis] = {axes[3 * axis], axes[3 * axis + 1], axes[3 * axis + 2]};
    glm::dvec3 origin(0.0);
    if (const std::string* o = header.find("space origin")) {
      const std::vector<double> p = numbers(*o);
      if (p.size() != 3) fail(file, "NRRD 'space origin' needs a 3D point: '" + *o + "'");
      origin = {p[0], p[1], p[2]};
    }
    const std::string space = header.find("space") ? lower(*header.find("space")) : "left-posterior-superior";
    if (space == "right-anterior-superior" || space == "ras") {
      volume.voxel_to_mm = glm::dmat4(axes_world);
      volume.voxel_to_mm[3] = glm::dvec4(origin, 1.0);
    } else if (space == "left-posterior-superior" || space == "lps" || space == "scanner-xyz" ||
               space == "3d-right-handed") {
      volume.voxel_to_mm = lps_to_ras(axes_world, origin);
    } else {
      fail(file,
           "NRRD space '" + space + "' is not read (right-anterior-superior or left-posterior-superior)");
    }
    volume.frame = "NRRD space directions and origin (" + space + ")";
  } else {
    const std::string* spacings = header.find("spacings");
    const std::vector<double> spacing = spacings ? numbers(*spacings) : std::vector<double>{1.0, 1.0, 1.0};
    if (spacing.size() != 3) fail(file, "NRRD 'spacings' needs three values");
    volume.voxel_to_mm = glm::dmat4(1.0);
    for (int axis = 0; axis < 3; ++axis) volume.voxel_to_mm[axis][axis] = spacing[std::size_t(axis)];
    volume.frame = spacings ? "NRRD spacings (no space)" : "NRRD voxels (no space, no spacings)";
  }
  return volume;
}

Volume load_metaimage(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot open it");
  Header header;
  std::string line;
  bool data_line = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto equals = line.find('=');
    if (equals == std::string::npos) fail(file, "not a MetaImage header line: '" + line.substr(0, 60) + "'");
    const std::string key = lower(trim(line.substr(0, equals)));
    header.fields[key] = trim(line.substr(equals + 1));
    if (key == "elementdatafile") {  // always the last header line
      data_line = true;
      break;
    }
  }
  if (!data_line) fail(file, "not a MetaImage file (no ElementDataFile line)");
  header.data_offset = std::size_t(in.tellg());
  const auto required = [&](const char* key, const char* name) -> const std::string& {
    const std::string* value = header.find(key);
    if (!value) fail(file, std::string("the MetaImage header has no ") + name);
    return *value;
  };
  if (numbers(required("ndims", "NDims")) != std::vector<double>{3.0})
    fail(file,
         "not a volume palpate reads: NDims " + required("ndims", "NDims") + " (3D scalar volumes only)");
  if (const std::string* channels = header.find("elementnumberofchannels");
      channels && numbers(*channels) != std::vector<double>{1.0})
    fail(file, "unsupported data type: " + *channels + " channels per voxel (a scalar volume is needed)");
  Volume volume;
  volume.source = file;
  const std::vector<double> sizes = numbers(required("dimsize", "DimSize"));
  check_size(sizes, file);
  volume.size = {int(sizes[0]), int(sizes[1]), int(sizes[2])};

  static const std::map<std::string, VoxelType> types = {
      {"met_char", VoxelType::int8},       {"met_uchar", VoxelType::uint8},
      {"met_short", VoxelType::int16},     {"met_ushort", VoxelType::uint16},
      {"met_int", VoxelType::int32},       {"met_uint", VoxelType::uint32},
      {"met_long", VoxelType::int32},      {"met_ulong", VoxelType::uint32},
      {"met_long_long", VoxelType::int64}, {"met_ulong_long", VoxelType::uint64},
      {"met_float", VoxelType::float32},   {"met_double", VoxelType::float64}};
  const std::string type = lower(required("elementtype", "ElementType"));
  const auto found = types.find(type);
  if (found == types.end()) fail(file, "unsupported data type " + required("elementtype", "ElementType"));
  VoxelData data;
  data.type = found->second;
  for (const char* key : {"elementbyteordermsb", "binarydatabyteordermsb"})
    if (const std::string* msb = header.find(key)) data.big_endian = lower(*msb) == "true";
  if (const std::string* compressed = header.find("compresseddata")) data.gzip = lower(*compressed) == "true";
  const std::string& data_file = required("elementdatafile", "ElementDataFile");
  if (lower(data_file) == "local") {
    data.file = file;
    data.offset = header.data_offset;
  } else {
    if (lower(data_file).starts_with("list") || data_file.find('%') != std::string::npos)
      fail(file, "MetaImage data split over several files is not read");
    data.file = file.parent_path() / data_file;
    if (const std::string* skip = header.find("headersize");
        skip && numbers(*skip) != std::vector<double>{0.0})
      fail(file, "MetaImage HeaderSize is not read");
  }
  volume.values = read_voxels(
      data, std::size_t(volume.size.x) * std::size_t(volume.size.y) * std::size_t(volume.size.z), file);

  std::vector<double> spacing{1.0, 1.0, 1.0}, origin{0.0, 0.0, 0.0}, axes{1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (const std::string* s = header.find("elementspacing")) spacing = numbers(*s);
  for (const char* key : {"offset", "position", "origin"})
    if (const std::string* o = header.find(key)) origin = numbers(*o);
  for (const char* key : {"transformmatrix", "rotation", "orientation"})
    if (const std::string* m = header.find(key)) axes = numbers(*m);
  if (spacing.size() != 3 || origin.size() != 3 || axes.size() != 9)
    fail(file, "MetaImage ElementSpacing, Offset and TransformMatrix need 3, 3 and 9 values");
  glm::dmat3 axes_lps;  // TransformMatrix: the direction of each axis in turn (ITK's convention)
  for (int axis = 0; axis < 3; ++axis)
    axes_lps[axis] =
        glm::dvec3(axes[3 * axis], axes[3 * axis + 1], axes[3 * axis + 2]) * spacing[std::size_t(axis)];
  volume.voxel_to_mm = lps_to_ras(axes_lps, {origin[0], origin[1], origin[2]});
  volume.frame = "MetaImage Offset, ElementSpacing and TransformMatrix (LPS)";
  return volume;
}

}  // namespace palpate::volume
