// semsim GPU ICP kernels (WGSL). One invocation per data (source) point, as in the 2009 paper:
// transform the point, find its bucket, search that bucket and its 26 neighbours for the closest
// model (target) point within the correspondence gate, then reduce the pairs in workgroup memory
// into the sums the CPU needs: for point-to-point the centred sums of the SVD step (R = V U^T
// from the 3x3 correlation matrix, t = c_m - R c_d), for point-to-plane the 6x6 normal equations.

const NONE: u32 = 0xffffffffu;
const WG: u32 = 128u;
const K: u32 = 30u; // values per pair (point-to-plane needs 30; point-to-point uses 18)

struct Params {
    transform: mat4x4<f32>,   // target_from_source
    origin: vec4<f32>,        // grid origin xyz, w = 1 / bucket size
    reference: vec4<f32>,     // xyz: centring point for the sums, w: max squared distance
    dims: vec4<u32>,          // buckets per axis, w: hash mask
    counts: vec4<u32>,        // x: source points, y: mode (0 p2p, 1 p2plane), z: kernel (0 none, 1 huber, 2 cauchy), w: partials
    kernel: vec4<f32>,        // x: kernel width k (m), z: sub-cells per bucket axis
    sensor: vec4<f32>,        // xyz: the source's sensor in the source frame, w: 1 = reject back faces
};

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> source: array<vec4<f32>>;  // xyz, w: prior weight
@group(0) @binding(2) var<storage, read> model: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> normals: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> keys: array<u32>;
@group(0) @binding(5) var<storage, read> vals: array<u32>;
@group(0) @binding(6) var<storage, read> starts: array<u32>;
@group(0) @binding(7) var<storage, read_write> corr: array<u32>;
@group(0) @binding(8) var<storage, read_write> dist2: array<f32>;
@group(0) @binding(9) var<storage, read_write> partials: array<f32>;
@group(0) @binding(10) var<storage, read_write> totals: array<f32>;

var<workgroup> sh: array<f32, 3840>; // WG * K (15 KiB, within the 16 KiB every device offers)

fn bucket_of(key: u32) -> u32 {
    let mask = params.dims.w;
    var s = (key * 2654435761u) & mask;
    loop {
        let k = keys[s];
        if (k == key) { return vals[s]; }
        if (k == NONE) { return NONE; }
        s = (s + 1u) & mask;
    }
    return NONE;
}

struct Hit { index: u32, d2: f32 };

// The 26 neighbour buckets, faces first, then edges, then corners (nearest first, so the bound
// shrinks early).
var<private> NEIGHBOURS: array<vec3<i32>, 26> = array<vec3<i32>, 26>(
    vec3<i32>(-1, 0, 0), vec3<i32>(1, 0, 0), vec3<i32>(0, -1, 0), vec3<i32>(0, 1, 0),
    vec3<i32>(0, 0, -1), vec3<i32>(0, 0, 1),
    vec3<i32>(-1, -1, 0), vec3<i32>(1, -1, 0), vec3<i32>(-1, 1, 0), vec3<i32>(1, 1, 0),
    vec3<i32>(-1, 0, -1), vec3<i32>(1, 0, -1), vec3<i32>(-1, 0, 1), vec3<i32>(1, 0, 1),
    vec3<i32>(0, -1, -1), vec3<i32>(0, 1, -1), vec3<i32>(0, -1, 1), vec3<i32>(0, 1, 1),
    vec3<i32>(-1, -1, -1), vec3<i32>(1, -1, -1), vec3<i32>(-1, 1, -1), vec3<i32>(1, 1, -1),
    vec3<i32>(-1, -1, 1), vec3<i32>(1, -1, 1), vec3<i32>(-1, 1, 1), vec3<i32>(1, 1, 1),
);

// Squared distance from p to the box [lo, lo + size].
fn box_d2(p: vec3<f32>, lo: vec3<f32>, size: f32) -> f32 {
    let d = max(max(lo - p, p - (lo + vec3<f32>(size))), vec3<f32>(0.0));
    return dot(d, d);
}

// Scans bucket cc: only its sub-cells that overlap the ball of the best distance so far.
fn scan_bucket(p: vec3<f32>, cc: vec3<i32>, best: ptr<function, Hit>) {
    let dims = vec3<i32>(params.dims.xyz);
    if (any(cc < vec3<i32>(0)) || any(cc >= dims)) { return; }
    let size = 1.0 / params.origin.w;
    let lo = params.origin.xyz + vec3<f32>(cc) * size;
    if (box_d2(p, lo, size) > (*best).d2) { return; }
    let key = u32(cc.x) + params.dims.x * (u32(cc.y) + params.dims.y * u32(cc.z));
    let b = bucket_of(key);
    if (b == NONE) { return; }
    let sub = i32(params.kernel.z);
    let leaf = size / f32(sub);
    let reach = sqrt((*best).d2);
    let a = clamp(vec3<i32>(floor((p - vec3<f32>(reach) - lo) / leaf)), vec3<i32>(0), vec3<i32>(sub - 1));
    let z = clamp(vec3<i32>(floor((p + vec3<f32>(reach) - lo) / leaf)), vec3<i32>(0), vec3<i32>(sub - 1));
    let base = b * u32(sub * sub * sub);
    for (var sz = a.z; sz <= z.z; sz++) {
        for (var sy = a.y; sy <= z.y; sy++) {
            for (var sx = a.x; sx <= z.x; sx++) {
                let k = base + u32(sx + sub * (sy + sub * sz));
                let first = starts[k];
                let end = starts[k + 1u];
                if (first == end) { continue; }
                if (box_d2(p, lo + vec3<f32>(f32(sx), f32(sy), f32(sz)) * leaf, leaf) > (*best).d2) { continue; }
                for (var j = first; j < end; j++) {
                    let d = model[j].xyz - p;
                    let d2 = dot(d, d);
                    if (d2 < (*best).d2 || (d2 == (*best).d2 && (*best).index != NONE && j < (*best).index)) {
                        *best = Hit(j, d2);
                    }
                }
            }
        }
    }
}

// The paper's bucket search: the query's bucket first, then its 26 neighbours (faces, edges,
// corners), skipping buckets and sub-cells farther than the best point so far. Exact for every
// neighbour within one bucket edge; with the bucket edge >= the correspondence gate, exact.
// `hint` (the point's correspondence in the previous iteration) is any model point: inside the
// gate it bounds the search from the start, which prunes almost every sub-cell once the
// transform changes little; the result is the same (smallest distance, then smallest index).
fn nearest(p: vec3<f32>, hint: u32) -> Hit {
    var best = Hit(NONE, params.reference.w);
    if (hint < arrayLength(&model)) {
        let d = model[hint].xyz - p;
        let d2 = dot(d, d);
        if (d2 < best.d2) { best = Hit(hint, d2); }
    }
    let g = clamp((p - params.origin.xyz) * params.origin.w, vec3<f32>(-4.0), vec3<f32>(params.dims.xyz) + vec3<f32>(4.0));
    let c = vec3<i32>(floor(g));
    scan_bucket(p, c, &best);
    for (var k = 0u; k < 26u; k++) {
        scan_bucket(p, c + NEIGHBOURS[k], &best);
    }
    return best;
}

fn robust_weight(r: f32) -> f32 {
    let k = params.kernel.x;
    let a = abs(r);
    if (params.counts.z == 1u) { return select(k / a, 1.0, a <= k); }
    if (params.counts.z == 2u) { return 1.0 / (1.0 + (r * r) / (k * k)); }
    return 1.0;
}

@compute @workgroup_size(128)
fn search_reduce(@builtin(global_invocation_id) gid: vec3<u32>,
                 @builtin(local_invocation_index) lid: u32,
                 @builtin(workgroup_id) wid: vec3<u32>) {
    let i = gid.x;
    for (var k = 0u; k < K; k++) { sh[lid * K + k] = 0.0; }
    if (i < params.counts.x) {
        let s = source[i].xyz;
        let p = (params.transform * vec4<f32>(s, 1.0)).xyz;
        let hit = nearest(p, corr[i]);
        // The nearest point stays the next iteration's hint even when the back-face test
        // rejects the pair; dist2 < 0 marks "no pair".
        corr[i] = hit.index;
        var paired = hit.index != NONE;
        if (paired && params.sensor.w > 0.5) {
            // A model surface whose oriented normal points away from the source's sensor is
            // seen from behind (the far face of a wall): no pair.
            let eye = (params.transform * vec4<f32>(params.sensor.xyz, 1.0)).xyz;
            paired = dot(normals[hit.index].xyz, eye - model[hit.index].xyz) >= 0.0;
        }
        dist2[i] = select(-1.0, hit.d2, paired);
        if (paired) {
            let q = model[hit.index].xyz - params.reference.xyz;
            let pc = p - params.reference.xyz;
            let o = lid * K;
            if (params.counts.y == 0u) {
                // Point-to-point: pairs (transformed data point, model point), centred on
                // `reference`, weighted by the robust kernel of the point distance.
                let w = robust_weight(sqrt(hit.d2)) * source[i].w;
                sh[o] = 1.0;
                sh[o + 1u] = w * pc.x; sh[o + 2u] = w * pc.y; sh[o + 3u] = w * pc.z;
                sh[o + 4u] = w * q.x; sh[o + 5u] = w * q.y; sh[o + 6u] = w * q.z;
                for (var a = 0u; a < 3u; a++) {
                    for (var b2 = 0u; b2 < 3u; b2++) {
                        sh[o + 7u + a * 3u + b2] = w * pc[a] * q[b2];
                    }
                }
                sh[o + 16u] = hit.d2;
                sh[o + 17u] = w;
            } else {
                // Point-to-plane: residual r = (p - q) . n, Jacobian J = [p x n, n] (about `reference`).
                let n = normals[hit.index].xyz;
                let r = dot(pc - q, n);
                let w = robust_weight(r) * source[i].w;
                var jac: array<f32, 6>;
                let cr = cross(pc, n);
                jac[0] = cr.x; jac[1] = cr.y; jac[2] = cr.z; jac[3] = n.x; jac[4] = n.y; jac[5] = n.z;
                sh[o] = 1.0;
                var m = 1u;
                for (var a = 0u; a < 6u; a++) {
                    for (var b2 = a; b2 < 6u; b2++) {
                        sh[o + m] = w * jac[a] * jac[b2];
                        m++;
                    }
                }
                for (var a = 0u; a < 6u; a++) { sh[o + 22u + a] = w * jac[a] * r; }
                sh[o + 28u] = w * r * r;
                sh[o + 29u] = hit.d2;
            }
        }
    }
    workgroupBarrier();
    for (var stride = WG / 2u; stride > 0u; stride = stride / 2u) {
        if (lid < stride) {
            for (var k = 0u; k < K; k++) { sh[lid * K + k] += sh[(lid + stride) * K + k]; }
        }
        workgroupBarrier();
    }
    if (lid == 0u) {
        for (var k = 0u; k < K; k++) { partials[wid.x * K + k] = sh[k]; }
    }
}

@compute @workgroup_size(128)
fn sum_partials(@builtin(local_invocation_index) lid: u32) {
    for (var k = 0u; k < K; k++) { sh[lid * K + k] = 0.0; }
    for (var j = lid; j < params.counts.w; j += WG) {
        for (var k = 0u; k < K; k++) { sh[lid * K + k] += partials[j * K + k]; }
    }
    workgroupBarrier();
    for (var stride = WG / 2u; stride > 0u; stride = stride / 2u) {
        if (lid < stride) {
            for (var k = 0u; k < K; k++) { sh[lid * K + k] += sh[(lid + stride) * K + k]; }
        }
        workgroupBarrier();
    }
    if (lid == 0u) {
        for (var k = 0u; k < K; k++) { totals[k] = sh[k]; }
    }
}
