// A file's vertex colours in one form, whichever format carried them (an
// OBJ's `v x y z r g b`, a PLY's red/green/blue properties), so that an
// export to another format keeps them: a coloured scan read as PLY and
// written as OBJ, or an OBJ's colours written as PLY or GLB.
#include <algorithm>
#include <array>
#include <cmath>

#include "anisoform/mesh_io.h"

namespace aniso {

namespace {

// The largest value of a PLY integer type, which stands for full intensity;
// 1 for the float types (colours in [0, 1]).
double full_intensity(const std::string& type) {
  if (type == "uchar" || type == "uint8") return 255.0;
  if (type == "char" || type == "int8") return 127.0;
  if (type == "ushort" || type == "uint16") return 65535.0;
  if (type == "short" || type == "int16") return 32767.0;
  if (type == "uint" || type == "uint32") return 4294967295.0;
  if (type == "int" || type == "int32") return 2147483647.0;
  return 1.0;
}

const VertexProperty* find_property(const VertexProperties& properties, const char* name) {
  for (const VertexProperty& property : properties) {
    if (property.name == name) return &property;
  }
  return nullptr;
}

}  // namespace

Eigen::MatrixX3d vertex_colors(const SurfaceAttributes& attributes, int vertex_count) {
  if (vertex_count > 0 && attributes.vertex_colors.rows() == vertex_count) return attributes.vertex_colors;
  const std::array<const VertexProperty*, 3> channels{find_property(attributes.vertex_properties, "red"),
                                                      find_property(attributes.vertex_properties, "green"),
                                                      find_property(attributes.vertex_properties, "blue")};
  Eigen::MatrixX3d colors;
  for (const VertexProperty* channel : channels) {
    if (!channel || channel->values.size() != static_cast<std::size_t>(vertex_count) || vertex_count == 0) {
      return colors;
    }
  }
  colors.resize(vertex_count, 3);
  for (int k = 0; k < 3; ++k) {
    const double scale = full_intensity(channels[k]->type);
    for (int i = 0; i < vertex_count; ++i) colors(i, k) = std::clamp(channels[k]->values[i] / scale, 0.0, 1.0);
  }
  return colors;
}

SurfaceAttributes attributes_for_format(const SurfaceAttributes& attributes, MeshFormat format, int vertex_count) {
  SurfaceAttributes out = attributes;
  if (format == MeshFormat::Obj && out.vertex_colors.rows() == 0) {
    out.vertex_colors = vertex_colors(attributes, vertex_count);
  } else if (format == MeshFormat::Ply && out.vertex_properties.empty()) {
    const Eigen::MatrixX3d colors = vertex_colors(attributes, vertex_count);
    if (colors.rows() > 0) {
      const char* names[3] = {"red", "green", "blue"};
      for (int k = 0; k < 3; ++k) {
        VertexProperty channel{names[k], "uchar", std::vector<double>(static_cast<std::size_t>(vertex_count))};
        for (int i = 0; i < vertex_count; ++i) {
          channel.values[static_cast<std::size_t>(i)] = std::round(std::clamp(colors(i, k), 0.0, 1.0) * 255.0);
        }
        out.vertex_properties.push_back(std::move(channel));
      }
    }
  }
  return out;
}

}  // namespace aniso
