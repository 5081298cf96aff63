// A file's header comments (attribution, licence) survive an edit: read from
// PLY `comment`/`obj_info` lines and an OBJ's or OFF's leading `#` block,
// written after the "written by anisoform" line into every format that has
// comments, cleaned so that none can break the header it lands in. The
// koala's CC BY attribution was dropped by every export.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "anisoform/mesh_io.h"
#include "cli_runner.h"
#include "test_support.h"

using aniso::MeshFormat;
using aniso::ReadResult;
using aniso::test::mesh_path;

namespace {

const std::string kKoalaAttribution =
    "derived: one Loop-subdivision step of odedstein-meshes objects/koala/koala.obj "
    "(CC BY 3.0, YahooJAPAN via Thingiverse)";

std::string written(const aniso::Mesh& mesh, const aniso::SurfaceAttributes& attributes, MeshFormat format,
                    bool binary = true) {
  aniso::WriteOptions options;
  options.binary = binary;
  options.attributes = &attributes;
  return aniso::write_mesh_to_memory(mesh, format, options);
}

ReadResult read_back(const std::string& bytes, MeshFormat format) {
  return aniso::read_mesh_from_memory(bytes.data(), bytes.size(), format);
}

}  // namespace

TEST_CASE("file comments: the koala's attribution is read and written into PLY, OBJ and OFF", "[io][comments]") {
  const ReadResult koala = aniso::read_mesh(mesh_path("large/koala_loop1_200k.ply"));
  REQUIRE(koala.attributes.comments == std::vector<std::string>{kKoalaAttribution});
  // The koala's attribution on a small mesh: the comments, not the size, are tested.
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");

  const std::string ply = written(spot, koala.attributes, MeshFormat::Ply);
  CHECK(ply.rfind("ply\nformat binary_little_endian 1.0\ncomment written by anisoform\ncomment " + kKoalaAttribution +
                      "\nelement vertex 829\n",
                  0) == 0);
  const std::string obj = written(spot, koala.attributes, MeshFormat::Obj);
  CHECK(obj.rfind("# written by anisoform\n# " + kKoalaAttribution + "\nv ", 0) == 0);
  const std::string off = written(spot, koala.attributes, MeshFormat::Off);
  CHECK(off.rfind("OFF\n# written by anisoform\n# " + kKoalaAttribution + "\n829 1654 0\n", 0) == 0);

  struct Case {
    MeshFormat format;
    bool binary;
  };
  for (const Case c : {Case{MeshFormat::Ply, true}, Case{MeshFormat::Ply, false}, Case{MeshFormat::Obj, false},
                       Case{MeshFormat::Off, false}}) {
    INFO(aniso::format_name(c.format) << (c.binary ? " binary" : " ascii"));
    const ReadResult once = read_back(written(spot, koala.attributes, c.format, c.binary), c.format);
    CHECK(once.attributes.comments == std::vector<std::string>{kKoalaAttribution});
    CHECK(once.mesh.V == spot.V);
    // Read and written again: the "written by" line does not pile up.
    const std::string twice = written(spot, once.attributes, c.format, c.binary);
    CHECK(read_back(twice, c.format).attributes.comments == std::vector<std::string>{kKoalaAttribution});
    CHECK(twice == written(spot, koala.attributes, c.format, c.binary));
  }
}

TEST_CASE("file comments: torus.obj's leading block goes to a PLY and an OFF in order, later comments stay",
          "[io][comments]") {
  const ReadResult torus = aniso::read_mesh(mesh_path("closed/torus.obj"));
  const std::vector<std::string> blender{"Blender v2.82 (sub 7) OBJ File: ''", "www.blender.org"};
  REQUIRE(torus.attributes.comments == blender);
  const std::string ply = written(torus.mesh, torus.attributes, MeshFormat::Ply, false);
  CHECK(ply.rfind("ply\nformat ascii 1.0\ncomment written by anisoform\ncomment Blender v2.82 (sub 7) OBJ File: ''\n"
                  "comment www.blender.org\nelement vertex ",
                  0) == 0);
  CHECK(read_back(ply, MeshFormat::Ply).attributes.comments == blender);
  CHECK(read_back(written(torus.mesh, torus.attributes, MeshFormat::Off), MeshFormat::Off).attributes.comments ==
        blender);

  // Only the header block: a comment among the data describes the data.
  const std::string obj = "# made by hand\n\n  # CC0\nv 0 0 0\n# 3 vertices\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK(read_back(obj, MeshFormat::Obj).attributes.comments == std::vector<std::string>{"made by hand", "CC0"});
  const std::string off = "# before\nOFF\n# between\n3 1 0\n# after the counts\n0 0 0\n# a vertex\n1 0 0\n0 1 0\n3 0 1 2\n";
  CHECK(read_back(off, MeshFormat::Off).attributes.comments ==
        std::vector<std::string>{"before", "between", "after the counts"});
}

TEST_CASE("file comments: control characters are spaces, 64 comments of 256 bytes at most", "[io][comments]") {
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");
  aniso::SurfaceAttributes attributes;
  attributes.comments = {"a\nend_header\nbroken", "b\r\nv 9 9 9", std::string("nul\0tab\tdel\x7f", 12),
                         std::string(1000, 'x'), "   ", "caf\xc3\xa9"};
  for (int i = 0; i < 100; ++i) attributes.comments.push_back("line " + std::to_string(i));
  std::vector<std::string> expected{"a end_header broken", "b  v 9 9 9", "nul tab del", std::string(256, 'x'),
                                    "caf\xc3\xa9"};
  for (int i = 0; expected.size() < 64; ++i) expected.push_back("line " + std::to_string(i));

  for (const MeshFormat format : {MeshFormat::Ply, MeshFormat::Obj, MeshFormat::Off}) {
    INFO(aniso::format_name(format));
    const ReadResult back = read_back(written(spot, attributes, format), format);
    CHECK(back.attributes.comments == expected);
    CHECK(back.mesh.V == spot.V);  // no `v 9 9 9` got in
    CHECK(back.mesh.F == spot.F);
  }
  // A long UTF-8 character at the cut is not split.
  std::vector<std::string> cut;
  aniso::keep_file_comment(cut, std::string(255, 'y') + "\xc3\xa9");
  CHECK(cut == std::vector<std::string>{std::string(255, 'y')});
}

TEST_CASE("file comments: binary STL's header takes the first comment when it fits whole", "[io][comments]") {
  const aniso::Mesh spot = aniso::test::load("formats/spot_lowres.obj");
  aniso::SurfaceAttributes attributes;
  attributes.comments = {"Spot by Keenan Crane, public domain"};
  std::string header = "binary STL written by anisoform; Spot by Keenan Crane, public domain";
  header.resize(80, ' ');
  CHECK(written(spot, attributes, MeshFormat::Stl).substr(0, 80) == header);
  attributes.comments = {kKoalaAttribution};
  CHECK(written(spot, attributes, MeshFormat::Stl).substr(0, 80) ==
        "binary STL written by anisoform" + std::string(49, ' '));
}

TEST_CASE("file comments: anisoform deform keeps the input's attribution", "[cli][comments]") {
  const std::string output = aniso::test::temp_path("spot_comments.ply");
  aniso::test::run_expecting({"deform", mesh_path("formats/spot_lowres_ascii.ply"), output, "--select", "all",
                              "--scale", "1.1", "--ascii"},
                             0);
  const ReadResult back = aniso::read_mesh(output);
  CHECK(back.attributes.comments ==
        std::vector<std::string>{"Converted by the curator from odedstein-meshes objects/spot/spot_low_resolution.obj "
                                 "(Spot by Keenan Crane, public domain)."});
}
