/* Collision plugins (kind TACTA_KIND_COLLISION): the function table and the data it sees.
 *
 * One table serves four roles; a plugin fills the entries of its roles, leaves the others NULL
 * and declares its roles in `roles` (TACTA_COLLISION_ROLE_* bits, the last member):
 *   broad phase  (bvh):    update (refit or rebuild) + find_pairs, overlap_shape, and the haptic
 *                          proxy queries sphere_cast and closest_point;
 *   narrow phase (ccd):    detect (exact continuous test on candidate pairs) and the primitive
 *                          queries vertex_face / edge_edge over one tick;
 *   convex       (convex): shape_query (shape against shape or triangle: distance, depth,
 *                          normal) and detect (shapes against surfaces);
 *   response:              respond (moves end positions so nothing penetrates, writes forces).
 *
 * Per tick the host passes a world view: deformable surfaces with their vertex positions at the
 * start of the tick and the proposed positions at its end (linear motion in between), rigid
 * convex shapes with a pose at start and end, and static obstacles. Plugins write results into
 * arrays the host owns, each with a capacity; nothing is allocated per tick: an instance
 * allocates in create() and in prepare(world), which the host calls at load time and again only
 * when the world's sizes change (a cut: a fresh instance is created, prepared and updated on
 * another thread while the one in use ticks, then takes its place; instances share nothing).
 * Per-tick entries return TACTA_COLLIDE_* bits, never throw.
 * Units: SI throughout (m, s, kg, N); times of impact are fractions of the tick in [0, 1].
 */
#ifndef TACTA_COLLISION_API_H
#define TACTA_COLLISION_API_H

#include "tacta/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TACTA_COLLISION_NONE 0xffffffffu /* an unused index (feature, node, body) */

/* ---- the world view --------------------------------------------------------------------------- */

/* A deformable body's collision surface. Arrays are owned by the host. Detection entries only
 * read; respond() writes positions_end and velocities. */
typedef struct tacta_collision_surface {
  uint32_t body_id;
  uint32_t vertex_count;
  const double* positions_start; /* 3 per vertex, m, at the start of the tick */
  double* positions_end;         /* 3 per vertex, m, proposed end of the tick (respond corrects) */
  double* velocities;            /* 3 per vertex, m/s, or NULL; respond updates them */
  const double* inverse_masses;  /* 1 per vertex, 1/kg, 0 = fixed; NULL = all 1 */
  uint32_t triangle_count;
  const uint32_t* triangles; /* 3 per triangle, outward, counter-clockwise */
  uint32_t tet_count;
  const uint32_t* tets; /* 4 per tet, or NULL (broad phase over volume elements) */
  double thickness;     /* m: contact distance kept between this surface and anything else */
} tacta_collision_surface;

typedef int32_t tacta_shape_type;
#define TACTA_SHAPE_SPHERE 1  /* radius about the pose origin */
#define TACTA_SHAPE_CAPSULE 2 /* segment of half_length along local z, swept by radius */
#define TACTA_SHAPE_BOX 3     /* half_extents along local x, y, z */
#define TACTA_SHAPE_HULL 4    /* convex hull of points (local frame), optionally grown by radius */
#define TACTA_SHAPE_PLANE 5   /* half-space below the plane n.x = offset (world), static only */

/* Rigid placement: world = position + R(rotation) local; rotation is a unit quaternion w,x,y,z. */
typedef struct tacta_pose {
  double position[3]; /* m */
  double rotation[4]; /* w, x, y, z */
} tacta_pose;

typedef struct tacta_collision_shape {
  uint32_t body_id;
  tacta_shape_type type;
  double radius;          /* m: sphere, capsule, rounding of a hull */
  double half_length;     /* m: capsule */
  double half_extents[3]; /* m: box */
  uint32_t point_count;
  const double* points;   /* hull: 3 per point, m, local frame */
  double plane_normal[3]; /* plane: unit outward normal (world) */
  double plane_offset;    /* plane: m */
  tacta_pose pose_start;  /* at the start of the tick */
  tacta_pose pose_end;    /* at the end of the tick (equal to pose_start when static) */
} tacta_collision_shape;

typedef struct tacta_collision_world {
  uint32_t struct_size;
  uint32_t surface_count;
  tacta_collision_surface* surfaces;
  uint32_t shape_count; /* moving rigid shapes, tools included (moved by the host, not by us) */
  const tacta_collision_shape* shapes;
  uint32_t obstacle_count; /* static obstacles: plane, box, hull */
  const tacta_collision_shape* obstacles;
  double dt;   /* s, the tick */
  double time; /* s, at the start of the tick */
  /* appended (read only when struct_size reaches it): m. The proxy queries (overlap_shape,
   * sphere_cast, closest_point) widen their search by it: the host has refit only part of a
   * surface's hierarchy since its vertices last moved (update_elements), and no vertex has moved
   * further than this from where its elements' boxes were computed. 0: every box is current. */
  double query_margin;
  /* appended (read only when struct_size reaches it), for the proxy queries of a plugin that
   * declares TACTA_COLLISION_PROXY_MAKES_CURRENT: before sphere_cast or closest_point reads a
   * triangle's positions_end, it calls make_current(make_current_context, surface, triangle),
   * which brings that triangle's vertices up to date (an embedded surface's vertices are current
   * only where made so). NULL: every position is current. Not thread-safe: call it from the
   * thread that called the query. */
  void (*make_current)(void* context, uint32_t surface, uint32_t triangle);
  void* make_current_context;
  /* appended (read only when struct_size reaches it), for the proxy queries of a plugin that
   * declares TACTA_COLLISION_PROXY_TAKES_CANDIDATES: when non-NULL, sphere_cast and
   * closest_point need test only these proxy_candidate_count triangles of the queried surface,
   * whose positions_end are current: the host has made sure no other triangle is within the
   * query's reach (the swept sphere's box; the box of max_distance about the point). NULL: the
   * whole surface, as above. */
  const uint32_t* proxy_candidates;
  uint32_t proxy_candidate_count;
} tacta_collision_world;

/* ---- results ---------------------------------------------------------------------------------- */

/* A broad-phase candidate: element (triangle, or tet when element_is_tet) of surface a against
 * element of surface b. surface_a == surface_b is a self-collision pair (adjacent excluded). */
typedef struct tacta_collision_pair {
  uint32_t surface_a, element_a;
  uint32_t surface_b, element_b;
} tacta_collision_pair;

typedef int32_t tacta_contact_type;
#define TACTA_CONTACT_VERTEX_FACE 1     /* vertex of a against triangle of b */
#define TACTA_CONTACT_EDGE_EDGE 2       /* edge of a against edge of b */
#define TACTA_CONTACT_SHAPE_VERTEX 3    /* vertex of surface a against shape b (tool, rigid) */
#define TACTA_CONTACT_OBSTACLE_VERTEX 4 /* vertex of surface a against obstacle b */
#define TACTA_CONTACT_SHAPE_SHAPE 5     /* shape a against shape or obstacle b (convex) */

/* Which array index_a / index_b refer to follows from the type: surfaces for deformable sides,
 * shapes for SHAPE_*, obstacles for OBSTACLE_*. Feature ids: vertex index, triangle index, or
 * an edge as triangle * 3 + local edge (edge k joins corners k and (k+1) % 3). */
typedef struct tacta_contact {
  tacta_contact_type type;
  uint32_t index_a, index_b;         /* into the world arrays (see above) */
  uint32_t body_a, body_b;           /* body ids */
  uint32_t feature_a, feature_b;     /* see above; TACTA_COLLISION_NONE when not applicable */
  uint32_t nodes_a[3], nodes_b[3];   /* vertices involved, TACTA_COLLISION_NONE padded */
  double weights_a[3], weights_b[3]; /* barycentric weights of the contact point on each side */
  double toi;                        /* time of impact as a fraction of the tick, [0, 1] */
  double point[3];                   /* m, on b's side at the end of the tick */
  double normal[3];                  /* unit, from b towards a: the direction that separates a */
  double depth;    /* m, penetration beyond the thickness (> 0 overlapping, <= 0 a gap) */
  double force[3]; /* N, on a (b gets the opposite), written by respond(): impulse / dt */
} tacta_contact;

/* The outcome of one primitive CCD query. */
typedef struct tacta_ccd_hit {
  double toi;            /* earliest time of contact, fraction of the tick; a lower bound */
  double barycentric[3]; /* vertex-face: weights of f0, f1, f2; edge-edge: s on a, t on b, 0 */
} tacta_ccd_hit;

/* Shape against shape, or shape against triangle, at the poses' end of tick. */
typedef struct tacta_shape_result {
  int32_t intersecting; /* 1 when the shapes overlap */
  double distance;      /* m, >= 0 when separate (0 when intersecting) */
  double depth;         /* m, penetration depth when intersecting, else 0 */
  double normal[3];     /* unit, from b towards a */
  double point_a[3];    /* m, deepest/closest point on a */
  double point_b[3];    /* m, deepest/closest point on b */
} tacta_shape_result;

/* A hit on a surface, for the haptic proxy. */
typedef struct tacta_surface_hit {
  uint32_t triangle;
  double barycentric[3];
  double toi;       /* sphere_cast: fraction of the segment, [0, 1]; closest_point: 0 */
  double point[3];  /* m, on the surface */
  double normal[3]; /* unit, the triangle's outward normal (towards the query) */
  double distance;  /* m: closest_point: from the query point; sphere_cast: 0 */
} tacta_surface_hit;

/* Per-tick result bits: 0 is success. */
#define TACTA_COLLIDE_OK 0u
#define TACTA_COLLIDE_OVERFLOW (1u << 0)   /* an output array was full; count is what fit */
#define TACTA_COLLIDE_NOT_FINITE (1u << 1) /* NaN or infinity in the input: those items skipped */
#define TACTA_COLLIDE_DEGENERATE (1u << 2) /* degenerate or out-of-range elements were skipped */
#define TACTA_COLLIDE_UNPREPARED (1u << 3) /* the world does not match prepare(); nothing done */
#define TACTA_COLLIDE_REBUILT (1u << 4)    /* info: the hierarchy was rebuilt, not refit */
#define TACTA_COLLIDE_UNRESOLVED (1u << 5) /* respond: some contact could not be resolved */

/* Roles a collision plugin serves (tacta_collision_api.roles). The engine picks one plugin per
 * role (a scene may name it: collision.plugins) and refuses a named plugin lacking the role. */
#define TACTA_COLLISION_ROLE_BROAD_PHASE (1u << 0)  /* update + find_pairs (+ overlap_shape) */
#define TACTA_COLLISION_ROLE_PROXY (1u << 1)        /* sphere_cast + closest_point (haptic proxy) */
#define TACTA_COLLISION_ROLE_NARROW_PHASE (1u << 2) /* detect on the broad phase's pairs */
#define TACTA_COLLISION_ROLE_RESPONSE (1u << 3)     /* respond */
#define TACTA_COLLISION_ROLE_COUNT 4u

/* What create() receives; valid only during create(). */
typedef struct tacta_collision_setup {
  uint32_t struct_size;
  const tacta_param_value* params; /* validated against the descriptor's schema, schema order */
  uint32_t param_count;
  double dt; /* s, the tick */
} tacta_collision_setup;

typedef struct tacta_collision_api {
  /* required: may allocate. Writes a reason on failure. */
  tacta_status (*create)(const tacta_collision_setup* setup, void** instance, char* message,
                         size_t message_capacity);
  /* required */
  void (*destroy)(void* instance);
  /* optional: allocate everything the per-tick entries need for this world (load time). Bad
   * meshes (indices out of range, NaN) are reported here with a message naming them. */
  tacta_status (*prepare)(void* instance, const tacta_collision_world* world, char* message,
                          size_t message_capacity);

  /* -- broad phase ---------------------------------------------------------------------------- */
  /* optional: refit (O(n)) or rebuild the hierarchies over the swept elements of this tick. */
  uint32_t (*update)(void* instance, const tacta_collision_world* world);
  /* optional: candidate pairs, body against body and self (adjacent elements excluded). */
  uint32_t (*find_pairs)(void* instance, const tacta_collision_world* world,
                         tacta_collision_pair* pairs, uint32_t capacity, uint32_t* count);
  /* optional: triangles of one surface whose swept box overlaps a tool shape's swept volume
   * (point = sphere of radius 0). */
  uint32_t (*overlap_shape)(void* instance, const tacta_collision_world* world,
                            const tacta_collision_shape* shape, uint32_t surface,
                            uint32_t* triangles, uint32_t capacity, uint32_t* count);
  /* optional, haptic proxy: first hit of a sphere (radius, m) moving from -> to against the end
   * of tick surface; returns 1 on a hit. */
  int32_t (*sphere_cast)(void* instance, const tacta_collision_world* world, uint32_t surface,
                         const double from[3], const double to[3], double radius,
                         tacta_surface_hit* hit);
  /* optional, haptic proxy: closest point of the end of tick surface to point within
   * max_distance (m); returns 1 when found. */
  int32_t (*closest_point)(void* instance, const tacta_collision_world* world, uint32_t surface,
                           const double point[3], double max_distance, tacta_surface_hit* hit);

  /* -- narrow phase --------------------------------------------------------------------------- */
  /* optional: contacts of the candidate pairs (pairs == NULL: every pair the role implies). */
  uint32_t (*detect)(void* instance, const tacta_collision_world* world,
                     const tacta_collision_pair* pairs, uint32_t pair_count,
                     tacta_contact* contacts, uint32_t capacity, uint32_t* count);
  /* optional: vertex v against triangle f0 f1 f2, each moving linearly over the tick. points:
   * v, f0, f1, f2 at the start, then the same at the end (8 x 3 doubles). Returns 1 on contact. */
  int32_t (*vertex_face)(void* instance, const double points[24], tacta_ccd_hit* hit);
  /* optional: edge a0 a1 against edge b0 b1; points: a0, a1, b0, b1 at start, then at end. */
  int32_t (*edge_edge)(void* instance, const double points[24], tacta_ccd_hit* hit);

  /* -- convex --------------------------------------------------------------------------------- */
  /* optional: a against b (b may be NULL when triangle, 9 doubles, is given instead). Returns
   * TACTA_COLLIDE_* bits. */
  uint32_t (*shape_query)(void* instance, const tacta_collision_shape* a,
                          const tacta_collision_shape* b, const double* triangle,
                          tacta_shape_result* result);

  /* -- response ------------------------------------------------------------------------------- */
  /* optional: correct the surfaces' positions_end (and velocities) so that no contact
   * penetrates beyond the thickness after the tick; writes each contact's force. */
  uint32_t (*respond)(void* instance, tacta_collision_world* world, tacta_contact* contacts,
                      uint32_t contact_count);

  /* TACTA_COLLISION_ROLE_* bits. Last on purpose: a plugin built against a header without it
   * has a shorter table (descriptor api_size) or leaves it 0, and the engine then guesses its
   * roles from the non-NULL entries (find_pairs: broad phase; sphere_cast and closest_point:
   * proxy; detect: narrow phase; respond: response), as it did before roles existed. */
  uint32_t roles;

  /* -- appended after roles (present when api_size reaches it) -------------------------------- */
  /* optional, broad phase (both or neither): a refit spread over several ticks. element_order
   * gives one surface's elements as its hierarchy keeps them (leaves in order), valid until the
   * next update() or prepare(); update_elements refits the elements order[first, first + count)
   * from the current positions and every ancestor from its children, so a run of that order is
   * a few whole subtrees and the paths above them. The host refits a run per tick, round-robin,
   * and sets query_margin to what the others may have moved since their boxes were computed.
   * Neither rebuilds; both return UNPREPARED before a first update() or for a hierarchy over
   * other elements than the surface's triangles. The host slices only a plugin that also
   * serves the proxy; then, for the proxy's queries, a surface's positions_end may be current
   * only for the triangles this plugin's overlap_shape (widened by query_margin) reports for the
   * query's box: the host brings those up to date before each query (or, with
   * TACTA_COLLISION_PROXY_MAKES_CURRENT, each triangle when the query calls make_current; with
   * TACTA_COLLISION_PROXY_TAKES_CANDIDATES, the candidates it names are current). */
  uint32_t (*element_order)(void* instance, uint32_t surface, const uint32_t** order,
                            uint32_t* count);
  uint32_t (*update_elements)(void* instance, const tacta_collision_world* world, uint32_t surface,
                              uint32_t first, uint32_t count);

  /* -- appended after update_elements (present when api_size reaches it) --------------------- */
  /* TACTA_COLLISION_PROXY_* bits. With MAKES_CURRENT, the proxy queries call the world's
   * make_current for each triangle before reading its positions, and the host then skips the
   * overlap_shape pass that made the query's whole box current (it reads only what is tested). */
  uint32_t proxy_flags;
} tacta_collision_api;

#define TACTA_COLLISION_PROXY_MAKES_CURRENT 1u
/* sphere_cast and closest_point read the world's proxy_candidates when set (tests only those),
 * and on equal distance (closest_point) or time of impact (sphere_cast) answer with the lowest
 * triangle index, so that the answer does not depend on the order triangles are tested in. */
#define TACTA_COLLISION_PROXY_TAKES_CANDIDATES 2u

#define TACTA_COLLISION_API_FIELD(member, required) \
  { #member, offsetof(tacta_collision_api, member), required }

static const tacta_api_field tacta_collision_api_fields[] = {
    TACTA_COLLISION_API_FIELD(create, 1),      TACTA_COLLISION_API_FIELD(destroy, 1),
    TACTA_COLLISION_API_FIELD(prepare, 0),     TACTA_COLLISION_API_FIELD(update, 0),
    TACTA_COLLISION_API_FIELD(find_pairs, 0),  TACTA_COLLISION_API_FIELD(overlap_shape, 0),
    TACTA_COLLISION_API_FIELD(sphere_cast, 0), TACTA_COLLISION_API_FIELD(closest_point, 0),
    TACTA_COLLISION_API_FIELD(detect, 0),      TACTA_COLLISION_API_FIELD(vertex_face, 0),
    TACTA_COLLISION_API_FIELD(edge_edge, 0),   TACTA_COLLISION_API_FIELD(shape_query, 0),
    TACTA_COLLISION_API_FIELD(respond, 0),     TACTA_COLLISION_API_FIELD(update_elements, 0),
    TACTA_COLLISION_API_FIELD(element_order, 0),
};

static inline const char* tacta_collision_role_name(uint32_t role) {
  switch (role) {
    case TACTA_COLLISION_ROLE_BROAD_PHASE: return "broad_phase";
    case TACTA_COLLISION_ROLE_PROXY: return "proxy";
    case TACTA_COLLISION_ROLE_NARROW_PHASE: return "narrow_phase";
    case TACTA_COLLISION_ROLE_RESPONSE: return "response";
    default: return "unknown";
  }
}

/* The roles a collision descriptor serves: its declared `roles`, or (a table without the member,
 * or 0) the roles its non-NULL entries imply; *guessed says which. */
static inline uint32_t tacta_collision_roles(const tacta_descriptor* d, int* guessed) {
  const tacta_collision_api* api = (const tacta_collision_api*)d->api;
  if (d->api_size >= offsetof(tacta_collision_api, roles) + sizeof(uint32_t) && api->roles != 0) {
    if (guessed) *guessed = 0;
    return api->roles;
  }
  if (guessed) *guessed = 1;
  uint32_t roles = 0;
  const size_t size = d->api_size;
#define TACTA_COLLISION_HAS(member) \
  (size >= offsetof(tacta_collision_api, member) + sizeof(void*) && api->member != NULL)
  if (TACTA_COLLISION_HAS(find_pairs)) roles |= TACTA_COLLISION_ROLE_BROAD_PHASE;
  if (TACTA_COLLISION_HAS(sphere_cast) && TACTA_COLLISION_HAS(closest_point))
    roles |= TACTA_COLLISION_ROLE_PROXY;
  if (TACTA_COLLISION_HAS(detect)) roles |= TACTA_COLLISION_ROLE_NARROW_PHASE;
  if (TACTA_COLLISION_HAS(respond)) roles |= TACTA_COLLISION_ROLE_RESPONSE;
#undef TACTA_COLLISION_HAS
  return roles;
}

#ifdef __cplusplus
}
#endif

#endif /* TACTA_COLLISION_API_H */
