// Runs after the libraries: logs the matrix calls a student's light makes (gl-matrix's mat4 and
// vec3, three.js's Matrix4 and cameras) with the line of their code that made each, and calls a
// light's CalcLightMVP as the framework's materials do. Keeps its own references to the built-ins
// it uses, so a page that replaces them cannot change what shadowlab reads.
"use strict";

(function () {
    const record = globalThis.__shadowlab;
    const stringify = JSON.stringify;
    const isView = ArrayBuffer.isView;
    const isArray = Array.isArray;
    const toNumber = Number;
    const log = [];
    let logging = false;

    function numbers(values, out) {
        for (const v of values) {
            if (out.length >= 64) break;
            if (typeof v === "number") out.push(v);
            else if ((isArray(v) || isView(v)) && v.length <= 16) for (let i = 0; i < v.length; i++) out.push(toNumber(v[i]));
            else if (v && typeof v === "object" && typeof v.x === "number") {
                out.push(v.x, v.y);
                if (typeof v.z === "number") out.push(v.z);
            }
        }
        return out;
    }

    function wrap(owner, key, name, skipOut) {
        const f = owner && owner[key];
        if (typeof f !== "function") return;
        owner[key] = function (...args) {
            if (logging && log.length < 4096) {
                const at = record.where();
                log.push({ name, args: numbers(skipOut ? args.slice(1) : args, []), file: at.file, line: at.line });
            }
            return f.apply(this, args);
        };
    }
    for (const lib of ["mat4", "vec3", "vec4", "quat"]) {
        const m = globalThis[lib];
        if (!m) continue;
        for (const key of Object.keys(m)) {
            // gl-matrix writes its result into the first argument of these; `create`-like ones take none.
            const takesOut = !/^(create|clone|fromValues|str|equals|exactEquals|length|len|dot|distance|dist|squaredLength|sqrLen|squaredDistance|sqrDist|angle)$/.test(key);
            wrap(m, key, lib + "." + key, takesOut);
        }
    }
    if (globalThis.THREE && THREE.Matrix4) {
        for (const key of ["makeOrthographic", "makePerspective", "lookAt", "multiplyMatrices", "multiply", "premultiply", "makeTranslation", "makeScale", "compose", "getInverse", "invert", "set"]) {
            wrap(THREE.Matrix4.prototype, key, "THREE.Matrix4." + key, false);
        }
    }
    if (globalThis.THREE) {
        for (const cls of ["OrthographicCamera", "PerspectiveCamera"]) {
            const C = THREE[cls];
            if (typeof C !== "function") continue;
            const logged = function (...args) {
                if (logging && log.length < 4096) {
                    const at = record.where();
                    log.push({ name: "THREE." + cls, args: numbers(args, []), file: at.file, line: at.line });
                }
                return Reflect.construct(C, args, new.target || logged);
            };
            logged.prototype = C.prototype;
            THREE[cls] = logged;
        }
    }

    // The parameter names of a function, lower-cased, from its source text.
    function parameters(f) {
        const text = Function.prototype.toString.call(f);
        const m = /^[^(]*\(([^)]*)\)/.exec(text);
        if (!m) return [];
        return m[1].split(",").map((p) => p.replace(/=.*$/, "").trim().toLowerCase()).filter((p) => p.length > 0);
    }

    // CalcLightMVP of the `index`th recorded light (or `light`) for an object placed by
    // `translate` and `scale`: parameters go by name (rot -> [0, 0, 0], trans, scal), others by
    // position. Returns JSON: {matrix: [16 numbers] | null, what: "…", calls: […]}.
    record.lightMatrix = function (light, translate, scale) {
        const found = light && light.CalcLightMVP;
        if (typeof found !== "function") return stringify({ matrix: null, what: "no CalcLightMVP method", calls: [] });
        const method = typeof found.__shadowlabOriginal === "function" ? found.__shadowlabOriginal : found;
        let names = parameters(method);
        const rest = names.some((n) => n.startsWith("..."));
        if (rest || names.length === 0) names = ["", ""];
        const args = names.map((n, i) => {
            if (n.includes("rot")) return [0, 0, 0];
            if (n.includes("trans")) return translate.slice();
            if (n.includes("scal")) return scale.slice();
            return [translate, scale][i] ? [translate, scale][i].slice() : undefined;
        });
        log.length = 0;
        logging = true;
        record.state.checking = true;
        let result;
        try {
            result = method.apply(light, args);
        } finally {
            logging = false;
            record.state.checking = false;
        }
        const calls = log.slice();
        if (result && typeof result === "object" && isArray(result.elements)) result = result.elements;
        let what;
        if (result === undefined) what = "undefined";
        else if (result === null) what = "null";
        else if (typeof result !== "object") what = "a " + typeof result;
        else if (!(isArray(result) || isView(result))) what = "an object";
        else if (result.length !== 16) what = "an array of " + result.length + " elements";
        if (what) return stringify({ matrix: null, what, calls });
        const matrix = [];
        for (let i = 0; i < 16; i++) {
            const v = result[i];
            if (typeof v !== "number") return stringify({ matrix: null, what: "an array whose element " + i + " is " + typeof v, calls });
            // JSON has no NaN or infinities: strings stand for them.
            matrix.push(v === v && v !== Infinity && v !== -Infinity ? v : String(v));
        }
        return stringify({ matrix, what: null, calls });
    };

    // The programs (their two shaders' sources) and the draws, as JSON.
    record.drawsJson = function () {
        const programs = record.programs.map((p) => {
            const source = (type) => (p.shaders.find((s) => s.type === type) || { source: null }).source;
            return { id: p.id, vertex: source(0x8b31), fragment: source(0x8b30) };
        });
        return stringify({ programs, draws: record.draws, requests: record.requests });
    };

    // The WebGL context the page asked for first ({kind, file, line}) and where it first made a
    // float texture ({file, line}), each or null, as JSON.
    record.contextJson = function () {
        return stringify({ context: record.state.context || null, floatTexture: record.state.floatTexture || null });
    };

    // The recorded lights as JSON (without their objects).
    record.lightsJson = function () {
        return stringify(record.lights.map((l) => ({ kind: l.kind, args: l.args, file: l.file, line: l.line, error: l.error })));
    };
})();
