// Runs a student's page from start to end, the same way whichever engine hosts it: their scripts
// in order, their first frames, then their light's CalcLightMVP for each object the check draws.
// The host gives `evalScript(name, text)`, which runs a classic script as global code named
// `name` in stack traces and throws what the script throws, and may give `step(file, what)`, told
// what runs next (a host that can only stop the page from outside names it in its message),
// `elapsedMs()`, the wall-clock time since the page started, and `engine`, its name.
// Returns the page's record as JSON (src/homework/page/mod.rs reads it).
"use strict";

(function () {
    const record = globalThis.__shadowlab;
    const stringify = JSON.stringify;
    const parse = JSON.parse;

    let memoryMiB = 0;
    // The page's other lights whose matrices are computed for checks of their own.
    const MAX_OTHER_LIGHTS = 7;
    // Whether the host's engine is QuickJS (the desktop's), whose three habits are undone below.
    let quickjs = false;
    // Each script's lines by file name, for placing an error the engine put on an earlier line.
    const linesOf = {};

    // QuickJS records a line only at names and calls: a property read through `this` or a
    // result (`this.light.lightPos`) is placed on the line of the last of those. Where the
    // property an error names is not on its line, the first line after it that reads it is.
    // An assignment to a constant is placed after it: the last line before that assigns it is.
    function placed(at, message) {
        const lines = linesOf[at.file];
        if (!quickjs || !lines || at.line < 1) return at.line;
        const constant = /^'([A-Za-z_$][\w$]*)' is read-only$/.exec(message);
        if (constant) {
            const name = constant[1].replace(/\$/g, "\\$");
            const assigns = new RegExp("(^|[^\\w$.])" + name + "\\s*([-+*/%&|^]|\\*\\*|<<|>>>?)?=(?!=)|(\\+\\+|--)\\s*" + name + "(?![\\w$])|(^|[^\\w$.])" + name + "\\s*(\\+\\+|--)");
            for (let i = at.line - 1; i >= Math.max(0, at.line - 40); i--) {
                if (assigns.test(lines[i]) && !/^\s*(const|let|var)\s/.test(lines[i])) return i + 1;
            }
            return at.line;
        }
        const m = /property '([A-Za-z_$][\w$]*)'/.exec(message);
        if (!m) return at.line;
        const name = m[1];
        const reads = (line) => line !== undefined && line.includes("." + name);
        if ((lines[at.line - 1] || "").includes(name)) return at.line;
        for (let i = at.line; i < Math.min(lines.length, at.line + 40); i++) {
            if (reads(lines[i])) return i + 1;
        }
        return at.line;
    }

    // A thrown value as {file, line, message}: the first stack frame in the student's code, the
    // engine's own words for a bound it hit replaced by which bound (QuickJS, out of memory with
    // no room left even for the error, throws null).
    function failure(e, fallbackFile) {
        let message = String(e && e.message !== undefined ? e.message : e).split(/[\r\n]/)[0];
        const at = record.theirFrame(e && e.stack) || { file: fallbackFile, line: 0, fn: "" };
        const within = at.fn ? " in " + at.fn : "";
        if (/^out of memory$|allocation failed|Array buffer allocation/i.test(message) || (e === null && quickjs)) {
            message = "the script used more than its memory bound" + (memoryMiB ? " of " + memoryMiB + " MiB" : "");
        } else if (/Maximum call stack size exceeded|stack overflow|too much recursion/i.test(message)) {
            message = "the script recursed deeper than its stack bound" + within + " (endless recursion?)";
        }
        return { file: at.file, line: placed(at, message), message };
    }

    // Lets the promise callbacks the page queued run (a loader's answer, an async material
    // build, each a few hops), as a browser does between one task and the next.
    async function settle() {
        for (let i = 0; i < 256; i++) await null;
    }
    const shown = (f) => (f.line > 0 ? f.file + ":" + f.line + ": " : f.file + ": ") + f.message;

    const WATCH =
        "try { if (typeof DirectionalLight === 'function') DirectionalLight = __shadowlab.watchLight('DirectionalLight', DirectionalLight); } catch (e) {}\n" +
        "try { if (typeof PointLight === 'function') PointLight = __shadowlab.watchLight('PointLight', PointLight); } catch (e) {}";

    function classProblem() {
        if (typeof globalThis.__shadowlabLightClass !== "function") return "no class or function named DirectionalLight";
        const proto = globalThis.__shadowlabLightClass.prototype;
        return proto && typeof proto.CalcLightMVP === "function" ? null : "DirectionalLight has no CalcLightMVP method";
    }

    // A light object with the template's fields, for a constructor that throws.
    function templateLight(args) {
        const light = Object.create(globalThis.__shadowlabLightClass.prototype);
        ["lightIntensity", "lightColor", "lightPos", "focalPoint", "lightUp", "hasShadowMap"].forEach((k, i) => {
            light[k] = args[i];
        });
        light.mesh = {};
        light.mat = {};
        light.fbo = {};
        return light;
    }

    // Each object's matrix under `object` (a light), or the error of computing it.
    function matricesOf(input, object) {
        return input.objects.map((o) => {
            try {
                return parse(record.lightMatrix(object, o.slice(0, 3), o.slice(3, 6)));
            } catch (e) {
                return { error: failure(e, input.light.name) };
            }
        });
    }

    // a * b for column-major 4x4 matrices (gl-matrix's layout).
    function times(a, b) {
        const out = new Array(16);
        for (let c = 0; c < 4; c++) {
            for (let r = 0; r < 4; r++) {
                let sum = 0;
                for (let k = 0; k < 4; k++) sum += a[k * 4 + r] * b[c * 4 + k];
                out[c * 4 + r] = sum;
            }
        }
        return out;
    }
    const same = (a, b) => Array.isArray(a) && Array.isArray(b) && a.length === 16 && b.length === 16
        && a.every((v, i) => Math.abs(v - b[i]) <= 1e-4 * (1 + Math.abs(b[i])));
    const matrixOf = (value) => {
        const numbers = Array.isArray(value) ? value.flat(2) : null;
        return numbers && numbers.length === 16 && numbers.every((v) => typeof v === "number") ? numbers : null;
    };
    // A light's projection * view: its CalcLightMVP for an object at the origin, unscaled.
    const viewProjection = (object) => {
        try {
            const m = parse(record.lightMatrix(object, [0, 0, 0], [1, 1, 1])).matrix;
            return Array.isArray(m) && m.every((v) => typeof v === "number") ? m : null;
        } catch (e) {
            return null;
        }
    };

    // Each made light's projection * view at the end of each frame the page ran (-1: as it
    // loaded), by the index of `record.lights`: a draw of frame f was made with the light as it
    // was at the end of frame f - 1 or of frame f (whether the page moves it before or after it
    // draws).
    let vpAt = {};
    function snapshot(frame) {
        vpAt[frame] = record.lights.map((l) => (l.object ? viewProjection(l.object) : null));
    }
    const vpsOf = (frame, index) =>
        [frame - 1, frame].map((f) => (vpAt[f] || [])[index]).filter((vp) => Array.isArray(vp));
    // uLightMVP (or any matrix uniform) `m` of a draw with model `model` is light `index`'s at `frame`.
    const isLights = (m, model, frame, index) =>
        vpsOf(frame, index).some((vp) => same(m, vp) || (model && same(m, times(vp, model))));

    // The first frame the page drew in (the one its uniforms are read from); 0 before any draw.
    const firstDrawnFrame = () => (record.draws.length ? Math.min(...record.draws.map((d) => d.frame)) : 0);

    // The draws of one frame whose uLightMVP no longer follows the page: a draw that matched a
    // light's matrix times its own uModelMatrix on the first frames, and now matches only the
    // light as it was (the light moved, its matrix was not computed again) or the object as it
    // was (the object moved). {kind: "light" | "object", light, request} each, once.
    function staleDraws(frame, lights) {
        const drawn = (f) => record.draws.filter((d) => d.frame === f);
        const firstFrame = firstDrawnFrame();
        const first = drawn(firstFrame);
        const ordinal = (list, d) => list.filter((o) => o.program === d.program && o.request === d.request).indexOf(d);
        const found = [];
        const now = drawn(frame);
        for (const d of now) {
            const mvp = matrixOf(d.uniforms.uLightMVP);
            const model = matrixOf(d.uniforms.uModelMatrix);
            const was = first.filter((o) => o.program === d.program && o.request === d.request)[ordinal(now, d)];
            const modelThen = was && matrixOf(was.uniforms.uModelMatrix);
            const mvpThen = was && matrixOf(was.uniforms.uLightMVP);
            if (!mvp || !model || !modelThen || !mvpThen) continue;
            const matchedThen = lights.some(([index]) => vpsOf(firstFrame, index).some((vp) => same(mvpThen, times(vp, modelThen))));
            if (!matchedThen || lights.some(([index]) => vpsOf(frame, index).some((vp) => same(mvp, times(vp, model))))) continue;
            let kind = null;
            let light = null;
            for (const [index] of lights) {
                const then = vpsOf(firstFrame, index);
                const current = vpsOf(frame, index);
                const moved = then.some((vp) => !current.some((c) => same(vp, c)));
                if (moved && then.some((vp) => same(mvp, times(vp, model)))) [kind, light] = ["light", index];
                else if (!same(model, modelThen) && current.concat(then).some((vp) => same(mvp, times(vp, modelThen)))) [kind, light] = ["object", index];
                if (kind) break;
            }
            if (kind && !found.some((f) => f.kind === kind && f.light === light && f.request === d.request)) {
                found.push({ kind, light, request: d.request });
            }
        }
        return found;
    }

    // Of a page with several lights with a map, each whose matrix no draw of the first frames
    // holds in any uniform (its uLightMVP, an element of an array, a name of the page's own;
    // times the draw's uModelMatrix, or alone): the page never draws with that light.
    function undrawnLights(out, light) {
        const lights = (out.checked === null ? [] : [[out.checked, light]])
            .concat(out.others.map((o) => [o.index, o.object]));
        if (lights.length < 2 || record.draws.length === 0) return;
        const firstFrame = firstDrawnFrame();
        const draws = record.draws.filter((d) => d.frame === firstFrame);
        const used = lights.map(([index]) =>
            vpsOf(firstFrame, index).length === 0 ||
            draws.some((d) => {
                const model = matrixOf(d.uniforms.uModelMatrix);
                return Object.values(d.uniforms).some((v) => {
                    const m = matrixOf(v);
                    return m && isLights(m, model, firstFrame, index);
                });
            }));
        if (!used.some((u) => u)) return;
        lights.forEach(([index], k) => {
            if (!used[k]) out.stale.push({ seconds: 0, kind: "none", light: index, request: null });
        });
    }

    // The page's animation: its frames run on to each time the check looks again (input.times,
    // seconds); there, each light whose matrices changed (an orbit, a light their code moves) is
    // kept in out.timed with its position then. Only a page whose lights move from frame to
    // frame is followed; its first frames' draws stay the ones read. The frames stop at half the
    // time bound (host.elapsedMs), with a note.
    async function followAnimation(host, input, out, light, runFrames, step) {
        out.timed = [];
        record.state.recordDraws = false;
        // Lights whose CalcLightMVP gave every matrix (one that failed is not run again).
        const lights = (out.checked === null ? [] : [[out.checked, light, out.matrices]])
            .concat(out.others.map((o) => [o.index, o.object, o.matrices]))
            .filter(([, , matrices]) => matrices.every((m) => Array.isArray(m.matrix)));
        // The matrices alone (not the calls that made them), to tell whether a light moved.
        const fingerprint = (matrices) => stringify(matrices.map((m) => m.matrix || null));
        const still = lights.map(([, , matrices]) => fingerprint(matrices));
        const elapsed = () => (typeof host.elapsedMs === "function" ? host.elapsedMs() : 0);
        const changed = (object, k) => fingerprint(matricesOf(input, object)) !== still[k];
        // Whether the models the page draws move: their uModelMatrix on a later frame.
        const models = (f) => stringify(record.draws.filter((d) => d.frame === f).map((d) => d.uniforms.uModelMatrix || null));
        // One frame more first: a page whose lights and models it leaves where they are is not
        // followed.
        const firstFrame = firstDrawnFrame();
        record.state.recordDraws = true;
        let frames = await runFrames(input.frames + 1);
        record.state.recordDraws = false;
        const modelsMove = record.draws.some((d) => d.frame === frames - 1) && models(frames - 1) !== models(firstFrame);
        if (!lights.some(([, object], k) => changed(object, k)) && !modelsMove) return;
        for (const seconds of input.times || []) {
            // The first frame whose clock reaches `seconds` is the last one run.
            const until = Math.ceil((seconds * 1000) / input.frameMs) + 1;
            if (elapsed() > input.timeMs / 2) {
                out.notes.push("the page's animation was followed to " + (((frames - 1) * input.frameMs) / 1000).toFixed(1) + " s only (half the time bound)");
                break;
            }
            frames = await runFrames(until - 1);
            record.state.recordDraws = true;
            frames = await runFrames(until);
            record.state.recordDraws = false;
            for (const stale of staleDraws(frames - 1, lights)) {
                out.stale.push(Object.assign({ seconds }, stale));
            }
            lights.forEach(([index, object], k) => {
                step(input.light.name, "CalcLightMVP at " + seconds + " s");
                const matrices = matricesOf(input, object);
                if (fingerprint(matrices) !== still[k]) {
                    out.timed.push({ index, seconds, position: record.plain(object && object.lightPos, 0), matrices });
                }
            });
        }
    }

    // input: {light: {name, text}, engineName, scripts: [{role, name, text}], files: {path: text},
    //         objects: [[tx, ty, tz, sx, sy, sz]], frames, frameMs}
    record.runPage = async function (host, inputJson) {
        const input = parse(inputJson);
        vpAt = {};
        memoryMiB = input.memoryMiB || 0;
        quickjs = host.engine === "quickjs";
        for (const script of input.scripts) linesOf[script.name] = script.text.split("\n");
        linesOf[input.light.name] = input.light.text.split("\n");
        const out = { fatal: null, notes: [], lights: [], checked: null, matrices: [], others: [], draws: null, context: null, stale: [], calcCalls: [] };
        Object.assign(record.files, input.files);
        let light = null;
        let lightRan = false;
        const runLight = () => {
            host.evalScript(input.light.name, input.light.text);
            host.evalScript("shadowlab/light_class.js", "globalThis.__shadowlabLightClass = typeof DirectionalLight === 'function' ? DirectionalLight : undefined;");
            lightRan = true;
        };
        for (const script of input.scripts) {
            try {
                if (script.role === "light") {
                    runLight();
                } else if (script.role === "engine") {
                    if (!lightRan) runLight();
                    const problem = classProblem();
                    if (problem) {
                        out.fatal = { file: input.light.name, line: 0, message: problem };
                        return stringify(out);
                    }
                    host.evalScript("shadowlab/watch.js", WATCH);
                    try {
                        host.evalScript(script.name, script.text);
                    } catch (e) {
                        out.notes.push(shown(failure(e, script.name)) + " (the rest of " + script.name + " did not run)");
                    }
                } else {
                    try {
                        host.evalScript(script.name, script.text);
                    } catch (e) {
                        const f = shown(failure(e, script.name));
                        out.notes.push(script.role === "ours"
                            ? "shadowlab's copy of " + script.name + " failed beside the page's own scripts (" + f + ")"
                            : f + " (the rest of " + script.name + " did not run)");
                    }
                }
            } catch (e) {
                // The light's own script failed: the check goes on with the framework's light.
                out.fatal = failure(e, input.light.name);
                return stringify(out);
            }
            await settle();
        }
        const step = (file, what) => {
            if (typeof host.step === "function") host.step(file, what);
        };
        let frameFailed = false;
        let frame = 0;
        const runFrames = async (until) => {
            for (; frame < until; frame++) {
                step("", "the page's frame " + frame + " (its requestAnimationFrame callbacks)");
                const frameError = record.runFrame(frame, input.frameMs);
                if (frameError && !frameFailed) {
                    frameFailed = true;
                    const [message, ...stack] = frameError.split("\n");
                    out.notes.push("a frame of the page failed: " + shown(failure({ message, stack: stack.join("\n") }, "")));
                }
                await settle();
                snapshot(frame);
            }
            return frame;
        };
        // Each light's matrices as the page loaded, before any frame moved it (what materials
        // built while loading hold).
        snapshot(-1);
        await runFrames(input.frames);

        const made = record.lights;
        // The lights with a shadow map of their own: every DirectionalLight, and a PointLight
        // whose class has a CalcLightMVP (the framework's has none: a lamp without a map).
        const casting = (l) =>
            l.kind === "DirectionalLight" || (l.object !== null && typeof l.object === "object" && typeof l.object.CalcLightMVP === "function");
        const directional = made.map((l, i) => [i, l]).filter(([, l]) => casting(l));
        if (directional.length === 0) {
            out.notes.push(input.engineName + " makes no DirectionalLight: used the framework's light");
            try {
                const gl = globalThis.document.querySelector("#glcanvas").getContext("webgl");
                light = new globalThis.__shadowlabLightClass(5000, [1, 1, 1], [0, 80, 80], [0, 0, 0], [0, 1, 0], true, gl);
            } catch (e) {
                out.notes.push("the DirectionalLight constructor failed (" + shown(failure(e, input.light.name)) + "); used an object with the template's fields instead");
                light = templateLight([5000, [1, 1, 1], [0, 80, 80], [0, 0, 0], [0, 1, 0], true]);
            }
        } else {
            const [index, first] = directional[0];
            if (directional.length > 1) {
                const kinds = [...new Set(directional.map(([, l]) => l.kind))].join(" and ");
                out.notes.push(first.file + " makes " + directional.length + " lights with a shadow map (" + kinds + "); the first (line " + first.line + ") is the one the check's main pictures show");
            }
            out.checked = index;
            if (first.error === null) {
                light = first.object;
            } else {
                out.notes.push("the DirectionalLight constructor failed (" + first.file + ":" + first.line + ": " + first.error + "); used an object with the template's fields instead");
                light = templateLight(first.args);
            }
        }
        out.lights = parse(record.lightsJson());
        step(input.light.name, "CalcLightMVP");
        out.matrices = matricesOf(input, light);
        // Where the light is once the first frames ran (an animation may have moved it already).
        out.position = record.plain(light && light.lightPos, 0);
        // Each other DirectionalLight the page made, for a check of its own (the bonus: one map
        // per light, each pass drawn with that light's matrices).
        for (const [index, other] of directional.slice(1, 1 + MAX_OTHER_LIGHTS)) {
            if (other.error !== null) continue;
            step(input.light.name, "CalcLightMVP of the light made on " + other.file + ":" + other.line);
            out.others.push({ index, matrices: matricesOf(input, other.object), object: other.object, position: record.plain(other.object.lightPos, 0) });
        }
        undrawnLights(out, light);
        await followAnimation(host, input, out, light, runFrames, step);
        out.others.forEach((o) => delete o.object);
        out.calcCalls = record.calcCalls.slice();
        out.draws = parse(record.drawsJson());
        out.context = parse(record.contextJson());
        return stringify(out);
    };

    // The page's own scripts cannot replace what shadowlab reads back.
    Object.freeze(record);
    Object.defineProperty(globalThis, "__shadowlab", { value: record, writable: false, configurable: false });
})();
