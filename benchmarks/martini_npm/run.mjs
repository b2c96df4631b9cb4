// benchmarks/martini_npm/run.mjs — @mapbox/martini (npm, the real package) on a
// terrain-RGB PNG padded to (2^k+1)^2, as martini's own test does: repeat the
// last row and column.  For each max error it prints martini's triangle and
// vertex counts and the mesh's TRUE max vertical error, found by evaluating every
// triangle's plane at every grid sample it covers (closed triangle, double
// precision, against the same float32 heights martini was given).
//
// Usage: node run.mjs PNG [MAX_ERROR...]      (default 10)
// Output: one line per max error:
//   martini_npm max_error=10 triangles=N vertices=N true_max_error=E at=(x,y) metric_ms=T mesh_ms=T
// PNG decoding uses node's zlib only (8-bit RGB/RGBA, non-interlaced).
import fs from 'fs';
import zlib from 'zlib';
import Martini from '@mapbox/martini';

function decodePng(buf) {
    const sig = [137, 80, 78, 71, 13, 10, 26, 10];
    for (let i = 0; i < 8; i++) if (buf[i] !== sig[i]) throw new Error('not a PNG');
    let pos = 8, width = 0, height = 0, depth = 0, ctype = 0, interlace = 0;
    const idat = [];
    while (pos < buf.length) {
        const len = buf.readUInt32BE(pos), type = buf.toString('latin1', pos + 4, pos + 8);
        const data = buf.subarray(pos + 8, pos + 8 + len);
        if (type === 'IHDR') {
            width = data.readUInt32BE(0); height = data.readUInt32BE(4);
            depth = data[8]; ctype = data[9]; interlace = data[12];
        } else if (type === 'IDAT') idat.push(data);
        else if (type === 'IEND') break;
        pos += 12 + len;
    }
    if (depth !== 8 || (ctype !== 2 && ctype !== 6) || interlace !== 0)
        throw new Error(`unsupported PNG: depth ${depth} colour type ${ctype} interlace ${interlace}`);
    const bpp = ctype === 6 ? 4 : 3, stride = width * bpp;
    const raw = zlib.inflateSync(Buffer.concat(idat));
    const out = new Uint8Array(width * height * 4);
    let prev = new Uint8Array(stride), cur = new Uint8Array(stride);
    for (let y = 0; y < height; y++) {
        const f = raw[y * (stride + 1)], row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
        for (let i = 0; i < stride; i++) {
            const a = i >= bpp ? cur[i - bpp] : 0, b = prev[i], c = i >= bpp ? prev[i - bpp] : 0;
            let p;
            switch (f) {
            case 0: p = 0; break;
            case 1: p = a; break;
            case 2: p = b; break;
            case 3: p = (a + b) >> 1; break;
            case 4: {
                const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
                p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c; break;
            }
            default: throw new Error(`bad PNG filter ${f}`);
            }
            cur[i] = (row[i] + p) & 255;
        }
        for (let x = 0; x < width; x++) {
            out[(y * width + x) * 4] = cur[x * bpp];
            out[(y * width + x) * 4 + 1] = cur[x * bpp + 1];
            out[(y * width + x) * 4 + 2] = cur[x * bpp + 2];
            out[(y * width + x) * 4 + 3] = bpp === 4 ? cur[x * bpp + 3] : 255;
        }
        [prev, cur] = [cur, prev];
    }
    return {width, height, data: out};
}

// martini's test/util.js decoding: float32 heights, pad right and bottom.
function terrainGrid(png) {
    const tile = png.width, size = tile + 1;
    if (png.height !== tile || (tile & (tile - 1))) throw new Error('need a square 2^k PNG');
    const t = new Float32Array(size * size);
    for (let y = 0; y < tile; y++)
        for (let x = 0; x < tile; x++) {
            const k = (y * tile + x) * 4;
            t[y * size + x] = (png.data[k] * 256 * 256 + png.data[k + 1] * 256.0 + png.data[k + 2]) / 10.0 - 10000.0;
        }
    for (let x = 0; x < size - 1; x++) t[size * (size - 1) + x] = t[size * (size - 2) + x];
    for (let y = 0; y < size; y++) t[size * y + size - 1] = t[size * y + size - 2];
    return {size, terrain: t};
}

function trueMaxError(size, terrain, vertices, triangles) {
    let best = 0, bx = -1, by = -1;
    for (let t = 0; t < triangles.length; t += 3) {
        const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
        const x0 = vertices[2 * a], y0 = vertices[2 * a + 1], x1 = vertices[2 * b], y1 = vertices[2 * b + 1];
        const x2 = vertices[2 * c], y2 = vertices[2 * c + 1];
        const z0 = terrain[y0 * size + x0], z1 = terrain[y1 * size + x1], z2 = terrain[y2 * size + x2];
        const D = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
        if (D === 0) continue;
        const s = D > 0 ? 1 : -1;
        for (let y = Math.min(y0, y1, y2); y <= Math.max(y0, y1, y2); y++)
            for (let x = Math.min(x0, x1, x2); x <= Math.max(x0, x1, x2); x++) {
                // integer barycentric weights (exact), plane in double
                const w0 = ((x2 - x1) * (y - y1) - (y2 - y1) * (x - x1)) * s;
                const w1 = ((x0 - x2) * (y - y2) - (y0 - y2) * (x - x2)) * s;
                const w2 = D * s - w0 - w1;
                if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                const e = Math.abs((w0 * z0 + w1 * z1 + w2 * z2) / (D * s) - terrain[y * size + x]);
                if (e > best) { best = e; bx = x; by = y; }
            }
    }
    return {best, bx, by};
}

const file = process.argv[2];
if (!file) { console.error('usage: node run.mjs PNG [MAX_ERROR...]'); process.exit(2); }
const errs = process.argv.length > 3 ? process.argv.slice(3).map(Number) : [10];
const {size, terrain} = terrainGrid(decodePng(fs.readFileSync(file)));
const martini = new Martini(size);
let tile = null;
const metric = [];
for (let r = 0; r < 11; r++) {           // median of 11 metric builds
    const t0 = process.hrtime.bigint();
    tile = martini.createTile(terrain);
    metric.push(Number(process.hrtime.bigint() - t0) / 1e6);
}
metric.sort((p, q) => p - q);
for (const e of errs) {
    const ms = [];
    let mesh = null;
    for (let r = 0; r < 11; r++) {
        const t0 = process.hrtime.bigint();
        mesh = tile.getMesh(e);
        ms.push(Number(process.hrtime.bigint() - t0) / 1e6);
    }
    ms.sort((p, q) => p - q);
    const te = trueMaxError(size, terrain, mesh.vertices, mesh.triangles);
    console.log(`martini_npm max_error=${e} triangles=${mesh.triangles.length / 3} vertices=${mesh.vertices.length / 2}` +
        ` true_max_error=${te.best.toFixed(4)} at=(${te.bx},${te.by}) metric_ms=${metric[5].toFixed(3)} mesh_ms=${ms[5].toFixed(3)}`);
}
