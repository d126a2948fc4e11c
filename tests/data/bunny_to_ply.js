// Converts the npm package bunny 1.0.1 (Mikola Lysenko's packaging of the Stanford bunny, see
// README.md here) into bunny.ply: binary little-endian PLY, vertex float x y z, face list uchar uint.
// Run by hand, once; the build never runs it:
//   mkdir /tmp/b && tar xzf bunny-1.0.1.tgz -C /tmp/b && node tests/data/bunny_to_ply.js /tmp/b/package tests/data/bunny.ply
// The positions are the package's decimal numbers rounded to the nearest float (Math.fround); the
// faces keep the package's order and winding.
'use strict';
const fs = require('fs');
const path = require('path');
if (process.argv.length !== 4) {
    console.error('usage: node bunny_to_ply.js <unpacked package folder> <out.ply>');
    process.exit(2);
}
const bunny = require(path.resolve(process.argv[2], 'index.js'));
const pkg = JSON.parse(fs.readFileSync(path.resolve(process.argv[2], 'package.json'), 'utf8'));
const positions = bunny.positions, cells = bunny.cells;
const header = [
    'ply',
    'format binary_little_endian 1.0',
    `comment ${pkg.name} ${pkg.version} (npm, licence: ${pkg.license}): the Stanford bunny`,
    'comment scan: Stanford Computer Graphics Laboratory, Stanford 3D Scanning Repository',
    `element vertex ${positions.length}`,
    'property float x',
    'property float y',
    'property float z',
    `element face ${cells.length}`,
    'property list uchar uint vertex_indices',
    'end_header',
    ''
].join('\n');
const head = Buffer.from(header, 'ascii');
const body = Buffer.alloc(positions.length * 12 + cells.length * 13);
let at = 0;
for (const p of positions) {
    if (p.length !== 3 || !p.every(Number.isFinite))
        throw new Error(`vertex ${at / 12} is not three finite numbers`);
    for (const x of p) {
        body.writeFloatLE(x, at);
        at += 4;
    }
}
cells.forEach((c, i) => {
    if (c.length !== 3 || !c.every(k => Number.isInteger(k) && k >= 0 && k < positions.length))
        throw new Error(`face ${i} is not a triangle of valid indices`);
    body.writeUInt8(3, at++);
    for (const k of c) {
        body.writeUInt32LE(k, at);
        at += 4;
    }
});
fs.writeFileSync(process.argv[3], Buffer.concat([head, body]));
console.log(`${process.argv[3]}: ${positions.length} vertices, ${cells.length} triangles`);
