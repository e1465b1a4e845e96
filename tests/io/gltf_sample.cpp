// gltf_sample OUT.glb OUT.expected.json: writes the test animation (tests/io/gltf_fixture.h) with
// writeGlb and, beside it, the vertices FaceSketch sampled, for the real-client tests
// (tools/gltf/validate.mjs, tools/gltf/three-check.mjs; tests/io/CMakeLists.txt).
#include "core/atomic_file.h"
#include "core/error.h"
#include "gltf_fixture.h"

#include <iostream>

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::cerr << "usage: gltf_sample OUT.glb OUT.expected.json\n";
        return 2;
    }
    try {
        const facesketch::GltfAnimation animation = facesketch::test::makeGltfTestAnimation();
        facesketch::writeGlb(argv[1], animation);
        const std::string expected = facesketch::test::gltfExpectations(animation).dump(2);
        facesketch::writeFileAtomically(argv[2], [&](std::ostream& out) { out << expected << "\n"; });
    } catch (const std::exception& e) {
        std::cerr << "gltf_sample: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
