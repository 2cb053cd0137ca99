#include "core/gifti_reader.hpp"

extern "C" {  // giftiio's header has no C++ guards
#include <gifti/gifti_io.h>
}
#include <expat.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>

#include "palpate/core/error.hpp"
#include "palpate/core/mesh.hpp"

namespace palpate::detail {
namespace {

// giftiio keeps global state (its verbosity, its parser buffers): one reader at a time.
std::mutex& gifti_mutex() {
  static std::mutex mutex;
  return mutex;
}

struct ImageDeleter {
  void operator()(gifti_image* image) const { gifti_free_image(image); }
};

// A gzipped .gii is inflated to a private temporary file: giftiio reads only named files.
class TemporaryCopy {
 public:
  TemporaryCopy(const std::string& content, const std::filesystem::path& file) {
    std::string name = (std::filesystem::temp_directory_path() / "palpate-gifti-XXXXXX").string();
    const int fd = ::mkstemp(name.data());
    if (fd < 0) throw Error(file, 0, "cannot create a temporary file to inflate it into");
    ::close(fd);
    path_ = name;
    std::ofstream out(path_, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    if (!out) throw Error(file, 0, "cannot write the inflated copy to " + path_.string());
  }
  ~TemporaryCopy() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The value at (row, column) of a rows x columns array in the array's own storage order.
template <class T>
T element(const giiDataArray& array, long long row, int column, long long rows, int columns) {
  const auto* values = static_cast<const T*>(array.data);
  return array.ind_ord == GIFTI_IND_ORD_COL_MAJOR ? values[column * rows + row]
                                                  : values[row * columns + column];
}

// giftiio reports malformed XML and bad base64 only on stderr, and then goes on with zeroed data;
// checking both first with expat gives a clear error and the line.
struct XmlCheck {
  XML_Parser parser = nullptr;
  bool in_base64_data = false;
  bool base64_array = false;
  int bad_base64_line = 0;
};

void XMLCALL on_start(void* user, const XML_Char* name, const XML_Char** attributes) {
  auto& check = *static_cast<XmlCheck*>(user);
  if (std::strcmp(name, "DataArray") == 0) {
    check.base64_array = false;
    for (int i = 0; attributes[i]; i += 2) {
      if (std::strcmp(attributes[i], "Encoding") == 0 && std::strstr(attributes[i + 1], "Base64"))
        check.base64_array = true;
    }
  }
  check.in_base64_data = check.base64_array && std::strcmp(name, "Data") == 0;
}

void XMLCALL on_end(void* user, const XML_Char*) {
  static_cast<XmlCheck*>(user)->in_base64_data = false;
}

void XMLCALL on_text(void* user, const XML_Char* text, int length) {
  auto& check = *static_cast<XmlCheck*>(user);
  if (!check.in_base64_data || check.bad_base64_line) return;
  for (int i = 0; i < length; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (!std::isalnum(c) && c != '+' && c != '/' && c != '=' && !std::isspace(c)) {
      check.bad_base64_line = static_cast<int>(XML_GetCurrentLineNumber(check.parser));
      return;
    }
  }
}

void check_xml(const std::string& content, const std::filesystem::path& file) {
  XmlCheck check;
  check.parser = XML_ParserCreate(nullptr);
  if (!check.parser) throw Error(file, 0, "expat could not start");
  XML_SetUserData(check.parser, &check);
  XML_SetElementHandler(check.parser, on_start, on_end);
  XML_SetCharacterDataHandler(check.parser, on_text);
  const bool ok = XML_Parse(check.parser, content.data(), static_cast<int>(content.size()), /*isFinal=*/1) ==
                  XML_STATUS_OK;
  const int line = static_cast<int>(XML_GetCurrentLineNumber(check.parser));
  const std::string reason = ok ? "" : XML_ErrorString(XML_GetErrorCode(check.parser));
  XML_ParserFree(check.parser);
  if (!ok) throw Error(file, line, "malformed GIfTI XML: " + reason);
  if (check.bad_base64_line) throw Error(file, check.bad_base64_line, "GIfTI data array is not valid base64");
}

const giiDataArray* find_array(const gifti_image& image, int intent) {
  for (int i = 0; i < image.numDA; ++i) {
    if (image.darray[i] && image.darray[i]->intent == intent) return image.darray[i];
  }
  return nullptr;
}

void require_n_by_3(const giiDataArray& array, const char* what, const std::filesystem::path& file) {
  if (array.num_dim != 2 || array.dims[1] != 3 || array.dims[0] <= 0 || !array.data) {
    throw Error(file, 0,
                std::string("GIfTI ") + what + " array is not N x 3 (" + std::to_string(array.num_dim) +
                    " dimensions, " + std::to_string(array.dims[0]) + " x " + std::to_string(array.dims[1]) +
                    ")");
  }
}

}  // namespace

Scene read_gifti_model(const std::string& content, bool was_gzip, const std::filesystem::path& file) {
  check_xml(content, file);
  std::lock_guard lock(gifti_mutex());
  std::unique_ptr<TemporaryCopy> copy;
  if (was_gzip) copy = std::make_unique<TemporaryCopy>(content, file);
  const std::string read_path = copy ? copy->path().string() : file.string();
  gifti_set_verb(0);  // giftiio prints its complaints to stderr otherwise; palpate reports its own
  std::unique_ptr<gifti_image, ImageDeleter> image(gifti_read_image(read_path.c_str(), 1));
  if (!image) {
    throw Error(
        file, 0,
        "giftiio could not read this GIfTI file (malformed XML, a data array that does not decode, or an "
        "encoding it does not support)");
  }
  const giiDataArray* points = find_array(*image, NIFTI_INTENT_POINTSET);
  const giiDataArray* triangles = find_array(*image, NIFTI_INTENT_TRIANGLE);
  if (!points || !triangles) {
    throw Error(file, 0,
                std::string("GIfTI file has no ") + (!points ? "POINTSET" : "TRIANGLE") +
                    " data array: it holds data on a surface, not the surface itself");
  }
  require_n_by_3(*points, "POINTSET", file);
  require_n_by_3(*triangles, "TRIANGLE", file);

  Mesh mesh;
  const long long vertex_count = points->dims[0];
  mesh.positions_mm.resize(static_cast<std::size_t>(vertex_count));
  for (long long v = 0; v < vertex_count; ++v) {
    for (int axis = 0; axis < 3; ++axis) {
      double value = 0.0;
      if (points->datatype == NIFTI_TYPE_FLOAT32) {
        value = element<float>(*points, v, axis, vertex_count, 3);
      } else if (points->datatype == NIFTI_TYPE_FLOAT64) {
        value = element<double>(*points, v, axis, vertex_count, 3);
      } else {
        throw Error(file, 0,
                    std::string("GIfTI POINTSET has data type ") + gifti_datatype2str(points->datatype) +
                        "; palpate reads FLOAT32 and FLOAT64");
      }
      if (!std::isfinite(value)) {
        throw Error(
            file, 0,
            "GIfTI POINTSET: vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or Inf)");
      }
      mesh.positions_mm[static_cast<std::size_t>(v)][axis] = static_cast<float>(value);
    }
  }
  const long long triangle_count = triangles->dims[0];
  mesh.indices.resize(static_cast<std::size_t>(triangle_count) * 3);
  for (long long t = 0; t < triangle_count; ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      long long index = 0;
      if (triangles->datatype == NIFTI_TYPE_INT32) {
        index = element<std::int32_t>(*triangles, t, corner, triangle_count, 3);
      } else if (triangles->datatype == NIFTI_TYPE_UINT32) {
        index = element<std::uint32_t>(*triangles, t, corner, triangle_count, 3);
      } else {
        throw Error(file, 0,
                    std::string("GIfTI TRIANGLE has data type ") + gifti_datatype2str(triangles->datatype) +
                        "; palpate reads INT32 and UINT32");
      }
      if (index < 0 || index >= vertex_count) {
        throw Error(file, 0,
                    "GIfTI TRIANGLE: triangle " + std::to_string(t) + " uses vertex " +
                        std::to_string(index) + ", but the POINTSET has " + std::to_string(vertex_count));
      }
      mesh.indices[static_cast<std::size_t>(t * 3 + corner)] = static_cast<std::uint32_t>(index);
    }
  }
  // giftiio leaves an array it could not inflate zeroed (and says so only on stderr).
  const Bounds extent = bounds(mesh);
  if (extent.size_mm() == glm::vec3(0.0f)) {
    throw Error(file, 0, "GIfTI POINTSET: all vertices are at one point (its data array did not decode?)");
  }
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a == b || b == c || a == c) {
      throw Error(file, 0,
                  "GIfTI TRIANGLE: triangle " + std::to_string(t / 3) + " repeats a vertex (" +
                      std::to_string(a) + ", " + std::to_string(b) + ", " + std::to_string(c) +
                      "): its data array did not decode?");
    }
  }
  compute_vertex_normals(mesh);
  Scene scene;
  SceneObject object;
  object.name = file.stem().string();
  object.source = file;
  object.mesh = std::move(mesh);
  scene.objects.push_back(std::move(object));
  return scene;
}

}  // namespace palpate::detail
