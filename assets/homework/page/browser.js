// What a student's page sees of a browser, for running their homework in shadowlab's sandbox:
// a window and document with one canvas, a WebGL context that records instead of drawing, the
// three.js loaders answered from shadowlab (never the network), and no timers that fire on their
// own. Runs before any library or student script; everything it keeps lives in `__shadowlab`.
// The Rust side reads `__shadowlab` back as JSON.
"use strict";

var window = globalThis;
var self = globalThis;

(function () {
    const record = {
        // Each `new DirectionalLight(...)` / `new PointLight(...)`: the class, the arguments (plain
        // numbers and arrays), where in the student's code it was made, and the object itself.
        lights: [],
        // Requests the page made that shadowlab answers or refuses: {what, url}.
        requests: [],
        // console.log and console.error lines (the first 200).
        console: [],
        // The callbacks requestAnimationFrame was given, in order (run only when shadowlab asks).
        frames: [],
        // Draw calls: {program, framebuffer, uniforms: {name: value}, count}.
        draws: [],
        programs: [],
        // The page's text files by path, as the loaders answer them (filled by the driver).
        files: {},
        // The frame being drawn (-1 while the page loads, then 0, 1, ...), the page's clock (ms)
        // and the WebGL context it asked for first; draws are recorded while `recordDraws` holds.
        state: { frame: -1, now: 0, context: null, floatTexture: null, recordDraws: true, checking: false },
        // Where the page itself calls a light's CalcLightMVP: {file, line, first, last} (frames;
        // -1 while it loads), one entry per place.
        calcCalls: [],
    };
    globalThis.__shadowlab = record;

    // The first frame of `stack` in a student's file (the libraries and shadowlab's own scripts
    // are not theirs): {file, line, fn}, fn "" at a script's top level; null where none is.
    record.theirFrame = function (stack, framework) {
        for (const frame of String(stack || "").split("\n")) {
            const m = /^\s*at\s+(?:(.*?)\s+\()?([^()\s]+?):(\d+)(?::\d+)?\)?\s*$/.exec(frame);
            if (!m) continue;
            const fn = m[1] && m[1] !== "<eval>" ? m[1] : "";
            // With `framework`, shadowlab's copy of the framework's own files counts too.
            if (framework && m[2].startsWith("shadowlab/framework/")) {
                return { file: "src/" + m[2].slice("shadowlab/framework/".length), line: Number(m[3]), fn, framework: true };
            }
            if (!record.ours(m[2])) return { file: m[2], line: Number(m[3]), fn };
        }
        return null;
    };
    // Where in the student's code the current call comes from: {file, line} ("" and 0: nowhere).
    record.where = function () {
        const at = record.theirFrame(new Error().stack);
        return at ? { file: at.file, line: at.line } : { file: "", line: 0 };
    };
    record.ours = function (file) {
        return file.startsWith("shadowlab/") || file.startsWith("lib/");
    };

    function plain(value, depth) {
        if (depth > 4) return null;
        if (typeof value === "number" || typeof value === "boolean" || typeof value === "string") return value;
        if (value === null || value === undefined) return null;
        if (ArrayBuffer.isView(value) && value.length <= 64) return Array.from(value);
        if (Array.isArray(value) && value.length <= 64) return value.map((v) => plain(v, depth + 1));
        if (typeof value === "object" && typeof value.x === "number" && typeof value.y === "number") {
            return typeof value.z === "number" ? [value.x, value.y, value.z] : [value.x, value.y];
        }
        return null;
    }
    record.plain = plain;

    // A light class wrapped so that each construction is recorded (same class, same prototype).
    record.watchLight = function (kind, cls) {
        if (typeof cls !== "function" || cls.__shadowlabWatched) return cls;
        // The page's own calls of CalcLightMVP (not the check's): where, and in which frames.
        const proto = cls.prototype;
        const method = proto && proto.CalcLightMVP;
        if (typeof method === "function" && !method.__shadowlabWatched) {
            const watchedMethod = function (...args) {
                if (!record.state.checking) {
                    const at = record.theirFrame(new Error().stack, true) || { file: "", line: 0 };
                    const frame = record.state.frame;
                    const seen = record.calcCalls.find((c) => c.file === at.file && c.line === at.line);
                    if (seen) seen.last = frame;
                    else if (record.calcCalls.length < 64) record.calcCalls.push({ file: at.file, line: at.line, framework: !!at.framework, first: frame, last: frame });
                }
                return method.apply(this, args);
            };
            watchedMethod.__shadowlabWatched = true;
            // The check reads the parameters' names and calls the page's own method.
            watchedMethod.__shadowlabOriginal = method;
            try {
                proto.CalcLightMVP = watchedMethod;
            } catch (e) {}
        }
        const watched = new Proxy(cls, {
            construct(target, args, newTarget) {
                const at = record.where();
                const entry = { kind, args: args.map((a) => plain(a, 0)), file: at.file, line: at.line, object: null, error: null };
                record.lights.push(entry);
                try {
                    entry.object = Reflect.construct(target, args, newTarget === watched ? target : newTarget);
                } catch (e) {
                    entry.error = String(e && e.message !== undefined ? e.message : e);
                    throw e;
                }
                return entry.object;
            },
            get(target, key, receiver) {
                return key === "__shadowlabWatched" ? true : Reflect.get(target, key, receiver);
            },
        });
        return watched;
    };

    const log = (kind) => (...args) => {
        if (record.console.length < 200) record.console.push(kind + ": " + args.map(String).join(" ").slice(0, 300));
    };
    globalThis.console = { log: log("log"), info: log("log"), warn: log("warn"), error: log("error"), debug: log("log"), assert: (c, ...a) => { if (!c) log("assert")(...a); }, time() {}, timeEnd() {} };
    globalThis.alert = log("alert");

    // A listener table that never fires on its own.
    const events = { addEventListener() {}, removeEventListener() {}, dispatchEvent() { return true; } };

    // The WebGL context: real constant values where the framework compares them, a recording of
    // programs, uniforms and draws, and a no-op for everything else.
    const GL = {
        DEPTH_BUFFER_BIT: 0x100, COLOR_BUFFER_BIT: 0x4000, TRIANGLES: 4, LEQUAL: 0x203, LESS: 0x201,
        CULL_FACE: 0xb44, DEPTH_TEST: 0xb71, BLEND: 0xbe2, TEXTURE_2D: 0xde1, UNSIGNED_BYTE: 0x1401,
        UNSIGNED_SHORT: 0x1403, UNSIGNED_INT: 0x1405, FLOAT: 0x1406, RGBA: 0x1908, RGB: 0x1907,
        DEPTH_COMPONENT: 0x1902, NEAREST: 0x2600, LINEAR: 0x2601, TEXTURE_MAG_FILTER: 0x2800,
        TEXTURE_MIN_FILTER: 0x2801, TEXTURE_WRAP_S: 0x2802, TEXTURE_WRAP_T: 0x2803, REPEAT: 0x2901,
        CLAMP_TO_EDGE: 0x812f, TEXTURE0: 0x84c0, ARRAY_BUFFER: 0x8892, ELEMENT_ARRAY_BUFFER: 0x8893,
        STATIC_DRAW: 0x88e4, DYNAMIC_DRAW: 0x88e8, FRAGMENT_SHADER: 0x8b30, VERTEX_SHADER: 0x8b31,
        COMPILE_STATUS: 0x8b81, LINK_STATUS: 0x8b82, FRAMEBUFFER: 0x8d40, RENDERBUFFER: 0x8d41,
        COLOR_ATTACHMENT0: 0x8ce0, DEPTH_ATTACHMENT: 0x8d00, FRAMEBUFFER_COMPLETE: 0x8cd5,
        DEPTH_COMPONENT16: 0x81a5, RGBA16F: 0x881a, RGBA32F: 0x8814, HALF_FLOAT: 0x140b,
        UNPACK_FLIP_Y_WEBGL: 0x9240, MAX_TEXTURE_SIZE: 0xd33, LINEAR_MIPMAP_LINEAR: 0x2703,
    };
    function context(canvas, kind) {
        let next = 1;
        // The bound program, framebuffer and buffers, and the model request of the last buffer
        // bound that holds one (a draw's model: its arrays came from a stand-in's answer).
        const state = { program: null, framebuffer: null, bound: {}, request: null };
        const make = (what, extra) => Object.assign({ __what: what, id: next++ }, extra || {});
        const uniform = (location, value) => {
            if (location && location.program) location.program.values[location.name] = plain(value, 0);
        };
        function draw(count) {
            const p = state.program;
            if (record.draws.length >= 4096 || !p || !record.state.recordDraws) return;
            record.draws.push({ frame: record.state.frame, program: p.id, framebuffer: state.framebuffer ? state.framebuffer.id : null, request: state.request, uniforms: Object.assign({}, p.values), count: Number(count) || 0 });
        }
        const methods = {
            canvas,
            drawingBufferWidth: canvas.width,
            drawingBufferHeight: canvas.height,
            getContextAttributes: () => ({ alpha: true, depth: true }),
            getExtension: (name) => ({ __extension: name }),
            getSupportedExtensions: () => ["WEBGL_depth_texture", "OES_texture_float"],
            getParameter: (p) => (p === GL.MAX_TEXTURE_SIZE ? 4096 : 0),
            isContextLost: () => false,
            createShader: (type) => make("shader", { type, source: "" }),
            shaderSource: (shader, source) => { if (shader) shader.source = String(source); },
            getShaderParameter: () => true,
            getShaderInfoLog: () => "",
            createProgram: () => {
                const p = make("program", { shaders: [], values: {} });
                record.programs.push(p);
                return p;
            },
            attachShader: (program, shader) => { if (program && shader) program.shaders.push(shader); },
            getProgramParameter: () => true,
            getProgramInfoLog: () => "",
            getUniformLocation: (program, name) => (program ? { program, name: String(name) } : null),
            getAttribLocation: (program, name) => 0,
            useProgram: (program) => { state.program = program; },
            bindFramebuffer: (target, fb) => { state.framebuffer = fb || null; },
            checkFramebufferStatus: () => GL.FRAMEBUFFER_COMPLETE,
            bindBuffer: (target, buffer) => {
                state.bound[target] = buffer || null;
                if (target === GL.ARRAY_BUFFER) state.request = buffer && typeof buffer.request === "number" ? buffer.request : null;
            },
            bufferData: (target, data) => {
                const buffer = state.bound[target];
                if (buffer && data && typeof data.shadowlabRequest === "number") {
                    buffer.request = data.shadowlabRequest;
                    state.request = buffer.request;
                }
            },
            // Where the page first makes a float texture (a map the check's RGBA8 passes cannot be).
            texImage2D: (target, level, internalformat, ...rest) => {
                const type = rest.length >= 6 ? rest[4] : rest[1];
                const floats = [GL.RGBA32F, GL.RGBA16F, 0x822e, 0x8230, 0x822d, 0x822f].includes(internalformat)
                    || [GL.FLOAT, GL.HALF_FLOAT, 0x8d61].includes(type);
                if (floats && !record.state.floatTexture) record.state.floatTexture = record.where();
            },
            drawElements: (mode, count) => draw(count),
            drawArrays: (mode, first, count) => draw(count),
        };
        for (const name of ["1f", "2f", "3f", "4f", "1i", "2i", "3i", "4i"]) {
            methods["uniform" + name] = (location, ...values) => uniform(location, values.length === 1 ? values[0] : values);
        }
        for (const name of ["1fv", "2fv", "3fv", "4fv", "1iv", "2iv", "3iv", "4iv"]) {
            methods["uniform" + name] = (location, value) => uniform(location, value);
        }
        for (const name of ["Matrix2fv", "Matrix3fv", "Matrix4fv"]) {
            methods["uniform" + name] = (location, transpose, value) => uniform(location, value);
        }
        return new Proxy(methods, {
            get(target, key) {
                if (key in target) return target[key];
                if (typeof key === "string" && key in GL) return GL[key];
                if (typeof key === "string" && /^[A-Z0-9_]+$/.test(key)) return 0x7000 + key.length;
                if (typeof key === "string" && key.startsWith("create")) return () => make(key.slice(6).toLowerCase());
                return () => undefined;
            },
        });
    }

    function element(tag) {
        const el = Object.assign(Object.create(events), {
            tagName: String(tag).toUpperCase(),
            style: {},
            width: 1280,
            height: 720,
            clientWidth: 1280,
            clientHeight: 720,
            children: [],
            appendChild(child) { this.children.push(child); return child; },
            removeChild(child) { return child; },
            setAttribute() {},
            getBoundingClientRect: () => ({ left: 0, top: 0, width: 1280, height: 720, right: 1280, bottom: 720 }),
            focus() {},
        });
        el.getContext = function (kind) {
            const k = String(kind);
            if (k !== "webgl" && k !== "experimental-webgl" && k !== "webgl2") return null;
            if (!record.state.context) record.state.context = Object.assign({ kind: k }, record.where());
            el.context = el.context || context(el, k);
            return el.context;
        };
        return el;
    }
    const canvas = element("canvas");
    const body = element("body");
    globalThis.document = Object.assign(Object.create(events), {
        body,
        documentElement: element("html"),
        querySelector: () => canvas,
        getElementById: () => canvas,
        getElementsByTagName: () => [canvas],
        createElement: (tag) => element(tag),
        createElementNS: (ns, tag) => element(tag),
    });
    // Own properties of the global object: in a browser's Worker some of these names are
    // read-only accessors of its prototype, which an assignment cannot replace.
    const define = (name, value) =>
        Object.defineProperty(globalThis, name, { value, writable: true, configurable: true, enumerable: true });
    for (const name of ["addEventListener", "removeEventListener", "dispatchEvent"]) define(name, events[name]);
    define("screen", { width: 1280, height: 720 });
    define("innerWidth", 1280);
    define("innerHeight", 720);
    define("devicePixelRatio", 1);
    define("navigator", { userAgent: "shadowlab" });
    define("location", { href: "shadowlab://homework/index.html", search: "", hash: "" });
    define("performance", { now: () => record.state.now });
    // The page's clock for Date too (animation code reads Date.now()): it starts at 0, so a run
    // is the same every time.
    const RealDate = Date;
    class PageDate extends RealDate {
        constructor(...args) {
            if (args.length === 0) super(record.state.now);
            else super(...args);
        }
        static now() {
            return record.state.now;
        }
    }
    define("Date", PageDate);
    // Runs frame `index` of the page, `step_ms` after the one before: the callbacks the previous
    // frame registered, as a browser does. Returns the first error (message, then its stack), or "".
    record.runFrame = function (index, step_ms) {
        let first = "";
        const callbacks = record.frames.splice(0);
        record.state.frame = index;
        record.state.now = index * step_ms;
        for (const callback of callbacks) {
            try {
                callback(record.state.now);
            } catch (e) {
                if (!first) first = String(e && e.message !== undefined ? e.message : e) + "\n" + String((e && e.stack) || "");
            }
        }
        return first;
    };
    define("requestAnimationFrame", (callback) => {
        if (typeof callback === "function" && record.frames.length < 16) record.frames.push(callback);
        return record.frames.length;
    });
    define("cancelAnimationFrame", () => {});
    define("setTimeout", () => 0);
    define("clearTimeout", () => {});
    define("setInterval", () => 0);
    define("clearInterval", () => {});
    const refuse = (what) => function (url) {
        record.requests.push({ what, url: String(url) });
        throw new Error(what + " is not available in shadowlab's check (" + String(url) + ")");
    };
    define("fetch", refuse("fetch"));
    define("XMLHttpRequest", function () { this.open = refuse("XMLHttpRequest"); this.send = () => {}; });
    define("Image", function () { return element("img"); });
    // What a browser's Worker has beyond a page's scripts: the network, other workers, storage,
    // and the channel the check's answer goes back on.
    for (const name of ["importScripts", "WebSocket", "EventSource", "Worker", "SharedWorker", "BroadcastChannel"]) {
        define(name, refuse(name));
    }
    for (const name of ["postMessage", "close"]) define(name, () => undefined);
    for (const name of ["indexedDB", "caches", "onmessage"]) define(name, undefined);
})();
