/*
 * primdecomp from C: decompose a mesh file (or, without one, a small bracket built
 * from float arrays), print the primitives and write an export.
 *
 *   cc decompose.c $(pkg-config --cflags --libs primdecomp) -o decompose
 *   ./decompose datasets/demo_scene.obj '{"targets": [150]}' demo.glb
 *
 * Arguments: [MESH [SETTINGS_JSON [OUT]]]. SETTINGS_JSON is the `settings` object a
 * result file carries (or any part of it): "{}" is the default run, the fewest
 * primitives within 2% of the mesh's diagonal. OUT's extension picks the format
 * (.json, .obj, .gltf, .glb, .urdf, .usda, .tscn, .mjcf).
 */
#include <primdecomp.h>
#include <stdio.h>
#include <string.h>

static int report(const char *stage, double fraction, int *last_percent) {
  int percent = (int)(100.0 * fraction);
  if (strcmp(stage, "merge") == 0 && percent / 25 != *last_percent / 25) {
    fprintf(stderr, "  merging: %d%%\n", percent);
  }
  *last_percent = percent;
  return 0; /* 0: go on; nonzero would cancel the run */
}

static int on_progress(void *user_data, const char *stage, double fraction) {
  return report(stage, fraction, (int *)user_data);
}

static int fail(const char *what, primdecomp_status status) {
  fprintf(stderr, "%s failed (status %d): %s\n", what, (int)status, primdecomp_last_error());
  return 1;
}

/* Two boxes forming an L-shaped bracket, as float arrays: 16 vertices, 12 quads. */
static primdecomp_status bracket(primdecomp_mesh **out) {
  static const float lo[2][3] = {{0, 0, 0}, {0, 0, 0}};
  static const float hi[2][3] = {{4, 0.5f, 2}, {0.5f, 3, 2}};
  static const uint32_t quad[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  float positions[2 * 8 * 3];
  uint32_t indices[2 * 6 * 4], sizes[2 * 6];
  for (int b = 0; b < 2; b++) {
    for (int c = 0; c < 8; c++) {
      for (int k = 0; k < 3; k++) {
        positions[(b * 8 + c) * 3 + k] = (c >> k & 1) ? hi[b][k] : lo[b][k];
      }
    }
    for (int f = 0; f < 6; f++) {
      sizes[b * 6 + f] = 4;
      for (int k = 0; k < 4; k++) indices[(b * 6 + f) * 4 + k] = b * 8 + quad[f][k];
    }
  }
  return primdecomp_mesh_from_floats(positions, 16, indices, 48, sizes, 12, out);
}

int main(int argc, char **argv) {
  const char *settings = argc > 2 ? argv[2] : "{}";
  printf("primdecomp %s\n", primdecomp_version());

  primdecomp_mesh *mesh = NULL;
  primdecomp_status s = argc > 1 ? primdecomp_mesh_load(argv[1], &mesh) : bracket(&mesh);
  if (s != PRIMDECOMP_STATUS_OK) return fail("loading the mesh", s);
  printf("mesh: %zu faces, %zu vertices\n", primdecomp_mesh_face_count(mesh),
         primdecomp_mesh_vertex_count(mesh));

  primdecomp_result *result = NULL;
  int last_percent = -1;
  s = primdecomp_decompose(mesh, settings, on_progress, &last_percent, NULL, &result);
  primdecomp_mesh_free(mesh); /* the result does not need the mesh */
  if (s != PRIMDECOMP_STATUS_OK) return fail("decomposing", s);

  primdecomp_level_info info;
  primdecomp_result_level(result, 0, &info);
  printf("%zu primitives, %zu bytes", info.primitives, info.bytes);
  if (info.distance == info.distance) {
    /* Under "solid": true on a closed mesh, a primitive's points inside it count as 0. */
    primdecomp_measured_to to = PRIMDECOMP_MEASURED_TO_MESH;
    primdecomp_result_level_measured_to(result, 0, &to);
    printf(", all within %g of the %s", info.distance,
           to == PRIMDECOMP_MEASURED_TO_SOLID ? "mesh's solid" : "mesh");
  }
  printf("\n");

  static const char *names[6] = {"box", "sphere", "capsule", "cylinder", "frustum", "prism"};
  const primdecomp_primitive *prims = NULL;
  size_t count = 0;
  primdecomp_result_primitives(result, 0, &prims, &count);
  for (size_t i = 0; i < count && i < 5; i++) {
    const primdecomp_primitive *p = &prims[i];
    printf("  %-8s (%u faces)", names[p->kind], p->faces);
    switch (p->kind) {
      case PRIMDECOMP_KIND_BOX:
        printf(" centre (%g, %g, %g), half extents (%g, %g, %g)", p->shape.box.center[0],
               p->shape.box.center[1], p->shape.box.center[2], p->shape.box.half_extents[0],
               p->shape.box.half_extents[1], p->shape.box.half_extents[2]);
        break;
      case PRIMDECOMP_KIND_SPHERE:
        printf(" radius %g", p->shape.sphere.radius);
        break;
      case PRIMDECOMP_KIND_CAPSULE:
        printf(" radius %g", p->shape.capsule.radius);
        break;
      case PRIMDECOMP_KIND_CYLINDER:
        printf(" radius %g", p->shape.cylinder.radius);
        break;
      case PRIMDECOMP_KIND_FRUSTUM:
        printf(" radii %g, %g", p->shape.frustum.radius0, p->shape.frustum.radius1);
        break;
      case PRIMDECOMP_KIND_PRISM:
        printf(" half length %g", p->shape.prism.half_x);
        break;
    }
    printf("\n");
  }
  if (count > 5) printf("  … and %zu more\n", count - 5);

  char *json = NULL;
  size_t len = 0;
  if ((s = primdecomp_result_json(result, 0, &json, &len)) != PRIMDECOMP_STATUS_OK) {
    primdecomp_result_free(result);
    return fail("writing the JSON", s);
  }
  printf("JSON: %zu bytes\n", len);
  primdecomp_string_free(json);

  if (argc > 3) {
    if ((s = primdecomp_result_export(result, 0, argv[3], NULL)) != PRIMDECOMP_STATUS_OK) {
      primdecomp_result_free(result);
      return fail("exporting", s);
    }
    printf("wrote %s\n", argv[3]);
  }
  primdecomp_result_free(result);
  return 0;
}
