#!/usr/bin/env perl
# make_corpus.pl OUT_DIR [SHARED_DATA_DIR]: writes the seed corpora of the fuzz targets into
# OUT_DIR/<target>/ (existing files are kept, so corpora grow across runs). Seeds are small files
# generated here, plus, when the shared data directory exists, files derived from it: its small
# GLB files as they are, its .gltf files with their buffers embedded as data URIs, and the first
# faces of each OBJ written as OBJ, PLY (ASCII and binary), OFF and STL (ASCII and binary).
use strict;
use warnings;
use File::Path qw(make_path);
use File::Basename qw(basename dirname);
use MIME::Base64 qw(encode_base64);

my ($out, $shared) = @ARGV;
die "usage: make_corpus.pl OUT_DIR [SHARED_DATA_DIR]\n" unless defined $out;

sub put {
    my ($target, $name, $bytes) = @_;
    make_path("$out/$target");
    open(my $f, '>:raw', "$out/$target/$name") or die "$out/$target/$name: $!\n";
    print $f $bytes;
    close($f);
}

sub slurp {
    my ($path) = @_;
    open(my $f, '<:raw', $path) or die "$path: $!\n";
    local $/;
    my $bytes = <$f>;
    close($f);
    return $bytes;
}

# --- meshes: one small mesh in every format the mesh loader reads ------------------------------
# The first byte of a fuzz_mesh_file input picks the extension: 0 obj, 1 ply, 2 off, 3 stl.
sub mesh_seeds {
    my ($name, $v, $f) = @_;    # vertices [[x,y,z]...], triangles [[a,b,c]...] (0-based)
    my $nv = @$v;
    my $nf = @$f;
    my $obj = join('', map { "v @$_\n" } @$v) . join('', map { 'f ' . join(' ', map { $_ + 1 } @$_) . "\n" } @$f);
    put('mesh_file', "$name.obj", "\x00" . $obj);
    my $ply = "ply\nformat ascii 1.0\nelement vertex $nv\nproperty float x\nproperty float y\nproperty float z\n"
        . "element face $nf\nproperty list uchar int vertex_indices\nend_header\n"
        . join('', map { "@$_\n" } @$v) . join('', map { "3 @$_\n" } @$f);
    put('mesh_file', "$name-ascii.ply", "\x01" . $ply);
    my $bply = "ply\nformat binary_little_endian 1.0\nelement vertex $nv\nproperty float x\nproperty float y\n"
        . "property float z\nelement face $nf\nproperty list uchar int vertex_indices\nend_header\n"
        . join('', map { pack('f<3', @$_) } @$v) . join('', map { pack('C l<3', 3, @$_) } @$f);
    put('mesh_file', "$name-binary.ply", "\x01" . $bply);
    my $off = "OFF\n$nv $nf 0\n" . join('', map { "@$_\n" } @$v) . join('', map { "3 @$_\n" } @$f);
    put('mesh_file', "$name.off", "\x02" . $off);
    my $stl = "solid $name\n";
    my $bstl = pack('a80 L<', "binary $name", $nf);
    for my $t (@$f) {
        my @p = map { $v->[$_] } @$t;
        $stl .= " facet normal 0 0 0\n  outer loop\n" . join('', map { "   vertex @$_\n" } @p) . "  endloop\n endfacet\n";
        $bstl .= pack('f<3', 0, 0, 0) . join('', map { pack('f<3', @$_) } @p) . pack('S<', 0);
    }
    put('mesh_file', "$name-ascii.stl", "\x03" . $stl . "endsolid $name\n");
    put('mesh_file', "$name-binary.stl", "\x03" . $bstl);
}

mesh_seeds('quad', [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]]);
mesh_seeds('tetra', [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]);
put('mesh_file', 'polygon-uv-normal.obj',
    "\x00# a quad with texture coordinates and normals\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      . "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -4 -3 -2\n");

# --- glTF: a triangle with a node hierarchy, extras and a collider -----------------------------
my $tri = pack('f<9', 0, 0, 0, 1, 0, 0, 0, 1, 0) . pack('S<3', 0, 1, 2) . "\0\0";
my $uri = 'data:application/octet-stream;base64,' . encode_base64($tri, '');
my $gltf = <<"JSON";
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
 "nodes":[{"name":"root","mesh":0,"children":[1,2],"extras":{"dynamic":true}},
          {"name":"UCX_root","mesh":0,"translation":[0,0,0.1]},
          {"name":"child","mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,2,0,0,1],"extras":{"decals":false}}],
 "meshes":[{"name":"tri","primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
 "materials":[{"name":"m","pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.5,1]}}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
 "buffers":[{"byteLength":44,"uri":"$uri"}]}
JSON
put('gltf', 'triangle.gltf', $gltf);
(my $external = $gltf) =~ s/"uri":"[^"]*"/"uri":"buffer.bin"/;
put('gltf', 'triangle-external.gltf', $external);
# The same as GLB: header, JSON chunk (padded with blanks), BIN chunk.
(my $json = $gltf) =~ s/,"uri":"[^"]*"//;
$json .= ' ' x ((4 - length($json) % 4) % 4);
my $bin = $tri;
put('gltf', 'triangle.glb',
    pack('a4 L< L<', 'glTF', 2, 12 + 8 + length($json) + 8 + length($bin))
      . pack('L< a4', length($json), 'JSON') . $json . pack('L< a4', length($bin), "BIN\0") . $bin);

# Nodes whose transforms single precision cannot trace (TraceTransform.hpp), one dynamic and one
# static beside a usable floor: the collision world must leave them out instead of handing them to
# Embree.
my %untraceable = (
    'columns-equal-in-float' => '"matrix":[1,1,0,0,1,1.000000001,0,0,0,0,1,0,0,2,0,1]',
    'nearly-singular'        => '"matrix":[1,0,0,0,1,0.00001,0,0,0,0,1,0,0,2,0,1]',
    'strong-shear'           => '"matrix":[1,0,0,0,1000000,1,0,0,0,0,1,0,0,2,0,1]',
    'scale-0'                => '"scale":[0,0,0],"translation":[0,2,0]',
    'scale-1e-20'            => '"scale":[1e-20,1e-20,1e-20]',
    'scale-1e20'             => '"scale":[1e20,1e20,1e20]',
    'mirrored-flat'          => '"scale":[-1,1,1e-9]');
for my $name (sort keys %untraceable) {
    my $t = $untraceable{$name};
    (my $doc = $gltf) =~ s/"scenes":\[\{"nodes":\[0\]\}\]/"scenes":[{"nodes":[0,1,2]}]/;
    $doc =~ s/"nodes":\[\{"name":"root".*?\}\],\n/"nodes":[{"name":"floor","mesh":0,"scale":[10,10,10]},{"name":"crate","mesh":0,$t,"extras":{"dynamic":true}},{"name":"prop","mesh":0,$t}],\n/s;
    put('gltf', "untraceable-$name.gltf", $doc);
}

# A triangle skinned to two joints and morphed by one target, animated by a LINEAR rotation, a
# CUBICSPLINE weights channel and a STEP translation: the animation part of the loader.
my $anim_bin = $tri                                              # 0: positions, 36: indices, pad
  . pack('C12', 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0)             # 44: JOINTS_0
  . pack('f<12', 1, 0, 0, 0, 0.5, 0.5, 0, 0, 1, 0, 0, 0)         # 56: WEIGHTS_0
  . pack('f<9', 0, 0, 1, 0, 0, 1, 0, 0, 1)                       # 104: target POSITION
  . pack('f<32', 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1) # 140: inverse bind matrices
  . pack('f<2', 0, 1)                                            # 268: key times
  . pack('f<8', 0, 0, 0, 1, 0, 0, 0.7071068, 0.7071068)          # 276: rotations
  . pack('f<6', 0, 0, 1, -1, 1, 0)                               # 308: cubic weights
  . pack('f<6', 0, 0, 0, 0, 1, 0);                               # 332: step translations
my $anim_uri = 'data:application/octet-stream;base64,' . encode_base64($anim_bin, '');
my $anim = <<"JSON";
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],
 "nodes":[{"name":"skinned","mesh":0,"skin":0},{"name":"joint0","children":[2]},
          {"name":"joint1","translation":[1,0,0]}],
 "skins":[{"joints":[1,2],"inverseBindMatrices":5}],
 "meshes":[{"weights":[0.25],"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":2,"WEIGHTS_0":3},
            "indices":1,"targets":[{"POSITION":4}]}]}],
 "animations":[{"name":"wave","samplers":[{"input":6,"output":7},
                {"input":6,"output":8,"interpolation":"CUBICSPLINE"},{"input":6,"output":9,"interpolation":"STEP"}],
   "channels":[{"sampler":0,"target":{"node":2,"path":"rotation"}},{"sampler":1,"target":{"node":0,"path":"weights"}},
               {"sampler":2,"target":{"node":1,"path":"translation"}}]}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"bufferView":0,"byteOffset":36,"componentType":5123,"count":3,"type":"SCALAR"},
              {"bufferView":0,"byteOffset":44,"componentType":5121,"count":3,"type":"VEC4"},
              {"bufferView":0,"byteOffset":56,"componentType":5126,"count":3,"type":"VEC4"},
              {"bufferView":0,"byteOffset":104,"componentType":5126,"count":3,"type":"VEC3"},
              {"bufferView":0,"byteOffset":140,"componentType":5126,"count":2,"type":"MAT4"},
              {"bufferView":0,"byteOffset":268,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},
              {"bufferView":0,"byteOffset":276,"componentType":5126,"count":2,"type":"VEC4"},
              {"bufferView":0,"byteOffset":308,"componentType":5126,"count":6,"type":"SCALAR"},
              {"bufferView":0,"byteOffset":332,"componentType":5126,"count":2,"type":"VEC3"}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":356}],
 "buffers":[{"byteLength":356,"uri":"$anim_uri"}]}
JSON
put('gltf', 'skinned-morphed-animated.gltf', $anim);
# The same with its morph target in a sparse accessor without a buffer view (one delta, its index
# read from the triangle's index data).
(my $sparse = $anim) =~ s/\{"bufferView":0,"byteOffset":104,("componentType":5126,"count":3,"type":"VEC3")\}/{$1,"sparse":{"count":1,"indices":{"bufferView":0,"byteOffset":36,"componentType":5123},"values":{"bufferView":0,"byteOffset":104}}}/;
put('gltf', 'skinned-sparse-morph.gltf', $sparse);
# A skin without its required "joints", which the parser refuses without a reason of its own.
(my $jointless = $anim) =~ s/"joints":\[1,2\],//;
put('gltf', 'skin-without-joints.gltf', $jointless);

# --- glTF geometry as exporters write it ---------------------------------------------------------
# A quad whose positions, indices and UVs are sparse: dense positions with vertex 2 wrong and one
# sparse value that puts it back, dense indices with one sparse replacement, and UVs in an accessor
# without a buffer view (zeros) with one sparse value.
my $sparse_bin = pack('f<12', 0, 0, 0, 1, 0, 0, 5, 5, 5, 0, 1, 0)   # 0: positions
  . pack('S<6', 0, 1, 3, 0, 2, 3)                                  # 48: indices
  . pack('S<2', 2, 0) . pack('f<3', 1, 1, 0)                        # 60: position index, 64: value
  . pack('S<2', 2, 0) . pack('S<2', 2, 0)                           # 76: index index, 80: value
  . pack('S<2', 3, 0) . pack('f<2', 0, 1);                          # 84: UV index, 88: value
my $sparse_uri = 'data:application/octet-stream;base64,' . encode_base64($sparse_bin, '');
put('gltf', 'sparse-geometry.gltf', <<"JSON");
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"name":"quad","mesh":0}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2},"indices":1}]}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",
               "sparse":{"count":1,"indices":{"bufferView":0,"byteOffset":60,"componentType":5123},
                         "values":{"bufferView":0,"byteOffset":64}}},
              {"bufferView":0,"byteOffset":48,"componentType":5123,"count":6,"type":"SCALAR",
               "sparse":{"count":1,"indices":{"bufferView":0,"byteOffset":76,"componentType":5123},
                         "values":{"bufferView":0,"byteOffset":80}}},
              {"componentType":5126,"count":4,"type":"VEC2",
               "sparse":{"count":1,"indices":{"bufferView":0,"byteOffset":84,"componentType":5123},
                         "values":{"bufferView":0,"byteOffset":88}}}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96}],
 "buffers":[{"byteLength":96,"uri":"$sparse_uri"}]}
JSON

# The triangle drawn three times by EXT_mesh_gpu_instancing (rotations in normalized shorts), with
# a material that is unlit and moves its texture coordinates (KHR_texture_transform).
my $inst_bin = $tri
  . pack('f<9', 0, 0, 0, 2, 0, 0, 0, 3, 1)                                       # 44: translations
  . pack('s<12', 0, 0, 0, 32767, 0, 0, 23170, 23170, 0, 0, 0, 32767)               # 80: rotations
  . pack('f<9', 1, 1, 1, 1, 1, 1, 2, 2, 2)                                       # 104: scales
  . pack('f<6', 0, 0, 1, 0, 0, 1);                                               # 140: UVs
my $inst_uri = 'data:application/octet-stream;base64,' . encode_base64($inst_bin, '');
put('gltf', 'instanced-transformed.gltf', <<"JSON");
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
 "extensionsUsed":["EXT_mesh_gpu_instancing","KHR_texture_transform","KHR_materials_unlit"],
 "extensionsRequired":["EXT_mesh_gpu_instancing","KHR_texture_transform"],
 "nodes":[{"name":"tri","mesh":0,"translation":[10,0,0],
           "extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":2,"ROTATION":3,"SCALE":4}}}}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":5},"indices":1,"material":0}]}],
 "materials":[{"extensions":{"KHR_materials_unlit":{}},
               "pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":
                 {"offset":[0.5,0],"rotation":0.39,"scale":[2,2]}}}}}],
 "textures":[{"source":0}],"images":[{"uri":"image.png"}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
              {"bufferView":0,"byteOffset":36,"componentType":5123,"count":3,"type":"SCALAR"},
              {"bufferView":0,"byteOffset":44,"componentType":5126,"count":3,"type":"VEC3"},
              {"bufferView":0,"byteOffset":80,"componentType":5122,"normalized":true,"count":3,"type":"VEC4"},
              {"bufferView":0,"byteOffset":104,"componentType":5126,"count":3,"type":"VEC3"},
              {"bufferView":0,"byteOffset":140,"componentType":5126,"count":3,"type":"VEC2"}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":164}],
 "buffers":[{"byteLength":164,"uri":"$inst_uri"}]}
JSON

# A quad compressed by libdraco (positions quantised to 11 bits), by its edgebreaker and its
# sequential coder: the accessors have no buffer view, as exporters write them.
my %draco = (
    'edgebreaker' => '445241434f02020101000000040200020000011fff011101ff0000010009030000020101010003030130011003002882980000000000ff0700000000000000000000000000000000803f0b',
    'sequential'  => '445241434f02020100000002040100010200020301010009030000020001010003030130011003003482880400000000ff0700000000000000000000000000000000803f0b');
for my $coder (sort keys %draco) {
    my $bytes = pack('H*', $draco{$coder});
    my $uri = 'data:application/octet-stream;base64,' . encode_base64($bytes, '');
    my $length = length($bytes);
    put('gltf', "draco-$coder.gltf", <<"JSON");
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"name":"quad","mesh":0}],
 "extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,
   "extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":0}}}}]}],
 "accessors":[{"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"componentType":5123,"count":6,"type":"SCALAR"}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":$length}],
 "buffers":[{"byteLength":$length,"uri":"$uri"}]}
JSON
}

# The quad compressed by meshoptimizer (EXT_meshopt_compression): positions by the vertex codec,
# indices by the index codec (TRIANGLES) or as an index sequence (INDICES), over a fallback buffer
# without a uri; as .gltf and as .glb.
my $mo_pos = pack('H*', 'a000000133000000ffff01330000007e7d0000010c000000ff010c0000007e000000000000000000000000000000000000000000000000000000000000000000000000');
my %mo_index = ('triangles' => ['TRIANGLES', pack('H*', 'e0f000007687566778a9866589689801690000')],
                'sequence'  => ['INDICES', pack('H*', 'd000040406080400000000')]);
for my $name (sort keys %mo_index) {
    my ($mode, $idx) = @{$mo_index{$name}};
    my $bin = $mo_pos . "\0" . $idx;                     # positions: 67 bytes, indices from 68
    $bin .= "\0" x ((4 - length($bin) % 4) % 4);
    my ($plen, $ilen, $blen) = (length($mo_pos), length($idx), length($bin));
    my $doc = <<"JSON";
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"name":"quad","mesh":0}],
 "extensionsUsed":["EXT_meshopt_compression"],"extensionsRequired":["EXT_meshopt_compression"],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"}],
 "bufferViews":[{"buffer":1,"byteOffset":0,"byteLength":48,"byteStride":12,
                 "extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":0,"byteLength":$plen,
                   "byteStride":12,"count":4,"mode":"ATTRIBUTES"}}},
                {"buffer":1,"byteOffset":48,"byteLength":24,
                 "extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":68,"byteLength":$ilen,
                   "byteStride":4,"count":6,"mode":"$mode"}}}],
 "buffers":[{"byteLength":$blen,"uri":"BUFFER0"},
            {"byteLength":72,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}]}
JSON
    (my $gltf_doc = $doc) =~ s/"BUFFER0"/'"data:application\/octet-stream;base64,' . encode_base64($bin, '') . '"'/e;
    put('gltf', "meshopt-$name.gltf", $gltf_doc);
    (my $glb_json = $doc) =~ s/,"uri":"BUFFER0"//;
    $glb_json .= ' ' x ((4 - length($glb_json) % 4) % 4);
    put('gltf', "meshopt-$name.glb",
        pack('a4 L< L<', 'glTF', 2, 12 + 8 + length($glb_json) + 8 + length($bin))
          . pack('L< a4', length($glb_json), 'JSON') . $glb_json . pack('L< a4', length($bin), "BIN\0") . $bin);
}

# --- ray lines ----------------------------------------------------------------------------------
put('ray_parser', 'rays.txt',
    "# origin and direction\n0 1 5 0 0 -1\n  -3.5e2\t1e-3 +7   0x1p-3 -0X1.8P+1 1  # hex\n\n"
      . "nan inf -inf 1 2 3\n1 2 3 4 5\n1 2 3 4 5 6 7\n0 0 0 1e-320 0 0\n1,2,3 4 5 6\n# only a comment\n");
put('ray_parser', 'crlf.txt', "0 0 0 0 0 -1\r\n1 1 1 1 1 1\r\n");

# --- spawn programs: deterministic pseudo-random bytes --------------------------------------------
my $state = 12345;
for my $k (1 .. 8) {
    my $bytes = '';
    for (1 .. 64 * $k) {
        $state = ($state * 1103515245 + 12345) % 2147483648;
        $bytes .= chr(($state >> 16) & 255);
    }
    put('spawn', "program-$k.bin", $bytes);
}

exit 0 unless defined $shared && -d $shared;

# --- derived from the shared data -----------------------------------------------------------------
for my $glb (glob("$shared/gltf/*/*.glb"), glob("$shared/gltf/*/models/*.glb")) {
    next if -s $glb > 256 * 1024;    # large files make every execution slow
    put('gltf', basename($glb), slurp($glb));
}
for my $path (glob("$shared/gltf/*/*.gltf")) {
    my $dir = dirname($path);
    my $text = slurp($path);
    $text =~ s{"uri"\s*:\s*"([^"]+\.bin)"}{
        my $file = "$dir/$1";
        -f $file ? '"uri": "data:application/octet-stream;base64,' . encode_base64(slurp($file), '') . '"' : "\"uri\": \"$1\""
    }ge;
    next if length($text) > 256 * 1024;
    put('gltf', basename($path), $text);
}
for my $path (glob("$shared/meshes/*.obj")) {
    my (@v, @f);
    open(my $in, '<', $path) or die "$path: $!\n";
    while (my $line = <$in>) {
        if ($line =~ /^v\s+(\S+)\s+(\S+)\s+(\S+)/) { push @v, [$1, $2, $3]; }
        elsif ($line =~ /^f\s+(\d+)\S*\s+(\d+)\S*\s+(\d+)/) { push @f, [$1 - 1, $2 - 1, $3 - 1]; last if @f >= 48; }
    }
    close($in);
    my (%map, @sv, @sf);
    for my $t (@f) {
        next if grep { $_ > $#v } @$t;
        push @sf, [map { $map{$_} //= do { push @sv, $v[$_]; $#sv } } @$t];
    }
    (my $name = basename($path)) =~ s/\.obj$//;
    mesh_seeds($name, \@sv, \@sf) if @sf;
}
