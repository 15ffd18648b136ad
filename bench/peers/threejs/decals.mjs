// The three.js decal workflow, timed on the mesh and rays of `spatter-bench tradeoff`: load the
// render mesh (OBJLoader), build a BVH over it (three-mesh-bvh), and for every ray raycast the mesh
// (acceleratedRaycast, first hit only) and build a DecalGeometry at the hit, as three.js's decal
// example does. Prints one JSON object (and writes it to --json FILE).
//
//   node decals.mjs --mesh MESH.obj --rays RAYS.txt --size S [--max-seconds T] [--seed N] [--json FILE]
//
// RAYS.txt: one ray per line, "ox oy oz dx dy dz". S: the decal's width, height and projection depth.
// Every ray is raycast first (timed as a whole), then a DecalGeometry is built at every hit in ray
// order until --max-seconds of wall time have passed (DecalGeometry visits every triangle of the
// mesh, so a large mesh takes long per decal); `decals` says how many were built. Times are CPU time
// of the process (user + system), with wall-clock figures beside them.

import fs from 'node:fs';
import { performance } from 'node:perf_hooks';
import * as THREE from 'three';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { DecalGeometry } from 'three/examples/jsm/geometries/DecalGeometry.js';
import { computeBoundsTree, acceleratedRaycast } from 'three-mesh-bvh';

function parseArgs(argv) {
    const args = { maxSeconds: 30, seed: 1 };
    for (let i = 2; i < argv.length; ++i) {
        const a = argv[i];
        const next = () => {
            if (i + 1 >= argv.length) throw new Error(`${a} needs a value`);
            return argv[++i];
        };
        if (a === '--mesh') args.mesh = next();
        else if (a === '--rays') args.rays = next();
        else if (a === '--size') args.size = Number(next());
        else if (a === '--max-seconds') args.maxSeconds = Number(next());
        else if (a === '--seed') args.seed = Number(next());
        else if (a === '--json') args.json = next();
        else throw new Error(`unknown argument ${a}`);
    }
    if (!args.mesh || !args.rays || !(args.size > 0)) throw new Error('--mesh, --rays and --size S > 0 are required');
    if (!(args.maxSeconds > 0)) throw new Error('--max-seconds must be positive');
    return args;
}

// A small seeded generator (the decals' random rotation about their axis), as the decal example's
// Math.random() but repeatable.
function makeRandom(seed) {
    let s = (seed >>> 0) || 1;
    return () => {
        s ^= s << 13;
        s >>>= 0;
        s ^= s >>> 17;
        s ^= s << 5;
        s >>>= 0;
        return s / 4294967296;
    };
}

function main() {
    const args = parseArgs(process.argv);
    const group = new OBJLoader().parse(fs.readFileSync(args.mesh, 'utf8'));
    const meshes = [];
    group.traverse((o) => {
        if (o.isMesh) meshes.push(o);
    });
    if (meshes.length !== 1) throw new Error(`${args.mesh}: expected one mesh, found ${meshes.length}`);
    const mesh = meshes[0];
    mesh.updateMatrixWorld(true);
    const geometry = mesh.geometry;
    const triangles = geometry.index ? geometry.index.count / 3 : geometry.attributes.position.count / 3;

    THREE.BufferGeometry.prototype.computeBoundsTree = computeBoundsTree;
    THREE.Mesh.prototype.raycast = acceleratedRaycast;
    const start = performance.now();
    geometry.computeBoundsTree();
    const bvhSeconds = (performance.now() - start) / 1000;

    const rays = fs
        .readFileSync(args.rays, 'utf8')
        .split('\n')
        .map((l) => l.trim())
        .filter((l) => l.length > 0)
        .map((l) => l.split(/\s+/).map(Number));

    const raycaster = new THREE.Raycaster();
    raycaster.firstHitOnly = true;
    const random = makeRandom(args.seed);
    const helper = new THREE.Object3D();
    const size = new THREE.Vector3(args.size, args.size, args.size);
    const origin = new THREE.Vector3();
    const direction = new THREE.Vector3();
    const normal = new THREE.Vector3();

    // Seconds of CPU time of the process (user and system), as spatter-bench reports its own.
    const cpuSeconds = () => {
        const u = process.cpuUsage();
        return (u.user + u.system) / 1e6;
    };

    // 1. Raycast every ray (the BVH query alone).
    const found = [];
    let wall = performance.now();
    let cpu = cpuSeconds();
    for (const r of rays) {
        origin.set(r[0], r[1], r[2]);
        direction.set(r[3], r[4], r[5]).normalize();
        raycaster.set(origin, direction);
        const hit = raycaster.intersectObject(mesh, false);
        found.push(hit.length > 0 && hit[0].face ? { point: hit[0].point, normal: hit[0].face.normal.clone(), ray: r } : null);
    }
    const raycastCpu = cpuSeconds() - cpu;
    const raycastWall = (performance.now() - wall) / 1000;
    const hits = found.filter((h) => h !== null).length;

    // 2. A DecalGeometry at every hit, in ray order, until --max-seconds of wall time have passed.
    let decals = 0;
    let vertices = 0;
    let capped = false;
    wall = performance.now();
    cpu = cpuSeconds();
    for (const h of found) {
        if (h === null) continue;
        if ((performance.now() - wall) / 1000 > args.maxSeconds) {
            capped = true;
            break;
        }
        direction.set(h.ray[3], h.ray[4], h.ray[5]).normalize();
        normal.copy(h.normal).transformDirection(mesh.matrixWorld);
        if (normal.dot(direction) > 0) normal.negate();
        helper.position.copy(h.point);
        helper.lookAt(h.point.clone().add(normal));
        const orientation = helper.rotation.clone();
        orientation.z = random() * 2 * Math.PI;
        const decal = new DecalGeometry(mesh, h.point, orientation, size);
        vertices += decal.attributes.position.count;
        decal.dispose();
        ++decals;
    }
    const decalCpu = cpuSeconds() - cpu;
    const decalWall = (performance.now() - wall) / 1000;

    const raycastNs = rays.length ? (raycastCpu * 1e9) / rays.length : null;
    const decalNs = decals ? (decalCpu * 1e9) / decals : null;
    const result = {
        peer: 'three.js',
        three_version: THREE.REVISION,
        node_version: process.version,
        triangles,
        bvh_build_s: bvhSeconds,
        rays: rays.length,
        hits,
        decals,
        capped,
        raycast_ns: raycastNs,
        decal_geometry_ns: decalNs,
        // One decal: the raycasts per placed decal plus its DecalGeometry (CPU time).
        per_decal_ns: decals && hits ? (raycastNs * rays.length) / hits + decalNs : null,
        raycast_wall_ns: rays.length ? (raycastWall * 1e9) / rays.length : null,
        decal_geometry_wall_ns: decals ? (decalWall * 1e9) / decals : null,
        decal_vertices_mean: decals ? vertices / decals : null,
    };
    const text = JSON.stringify(result, null, 2);
    if (args.json) fs.writeFileSync(args.json, text + '\n');
    process.stdout.write(text + '\n');
}

try {
    main();
} catch (e) {
    process.stderr.write(`decals.mjs: ${e.message}\n`);
    process.exit(1);
}
