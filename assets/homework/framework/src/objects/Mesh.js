// shadowlab's own copy of the framework's interface: vertex arrays by attribute name, and the
// object's translation and scale.
class TRSTransform {
    constructor(translate = [0, 0, 0], scale = [1, 1, 1]) {
        this.translate = translate;
        this.scale = scale;
    }
}

class Mesh {
    constructor(verticesAttrib, normalsAttrib, texcoordsAttrib, indices, transform) {
        this.indices = indices;
        this.count = indices.length;
        this.hasVertices = !!verticesAttrib;
        this.hasNormals = !!normalsAttrib;
        this.hasTexcoords = !!texcoordsAttrib;
        const t = transform || {};
        this.transform = new TRSTransform(
            [t.modelTransX || 0, t.modelTransY || 0, t.modelTransZ || 0],
            [t.modelScaleX === undefined ? 1 : t.modelScaleX, t.modelScaleY === undefined ? 1 : t.modelScaleY, t.modelScaleZ === undefined ? 1 : t.modelScaleZ]);
        const extraAttribs = [];
        for (const [field, attrib] of [['vertices', verticesAttrib], ['normals', normalsAttrib], ['texcoords', texcoordsAttrib]]) {
            if (attrib) {
                this[field] = attrib.array;
                this[field.slice(0, -1) + 'Name'] = attrib.name;
                extraAttribs.push(attrib.name);
            }
        }
        this.vertexName = verticesAttrib ? verticesAttrib.name : undefined;
        this.normalName = normalsAttrib ? normalsAttrib.name : undefined;
        this.texcoordName = texcoordsAttrib ? texcoordsAttrib.name : undefined;
        this.extraAttribs = extraAttribs;
    }

    static cube(transform) {
        const positions = [];
        const normals = [];
        const indices = [];
        // Six faces, each two triangles, in [-1, 1].
        for (const [axis, sign] of [[0, 1], [0, -1], [1, 1], [1, -1], [2, 1], [2, -1]]) {
            const u = (axis + 1) % 3;
            const v = (axis + 2) % 3;
            const base = positions.length / 3;
            for (const [a, b] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
                const p = [0, 0, 0];
                const n = [0, 0, 0];
                p[axis] = sign;
                p[u] = a;
                p[v] = b;
                n[axis] = sign;
                positions.push(...p);
                normals.push(...n);
            }
            indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
        }
        return new Mesh({ name: 'aVertexPosition', array: new Float32Array(positions) },
            { name: 'aNormalPosition', array: new Float32Array(normals) }, null, indices, transform);
    }
}
