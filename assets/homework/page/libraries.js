// The framework's libraries that touch the browser, as shadowlab stands them in after three.js and
// gl-matrix have loaded: OrbitControls (no input ever arrives), the three.js loaders (a request is
// recorded and answered only from what shadowlab holds; never the network) and dat.gui (controls
// that keep their values).
"use strict";

(function () {
    const record = globalThis.__shadowlab;
    const THREE = globalThis.THREE || (globalThis.THREE = {});

    THREE.OrbitControls = function (camera, element) {
        this.object = camera;
        this.domElement = element;
        this.target = THREE.Vector3 ? new THREE.Vector3() : { x: 0, y: 0, z: 0, set() {} };
        this.enabled = true;
        this.update = () => false;
        this.addEventListener = () => {};
        this.dispose = () => {};
        this.saveState = () => {};
        this.reset = () => {};
    };

    // A request answered from what shadowlab holds, a moment later as a browser would: a text
    // file from `record.files` (the submission's own by path, else the framework's), a model as a
    // small stand-in mesh tagged with the request, a material library and an image as stand-ins.
    // A file shadowlab does not hold stays unanswered.
    function answer(what, url, onLoad, manager) {
        const path = String(url).replace(/^(\.\/)+/, "").replace(/^\//, "");
        const request = record.requests.length;
        record.requests.push({ what, url: path });
        // As three.js's loaders tell their LoadingManager: the item starts now, and ends after
        // its onLoad ran (a page may wait for the manager's onProgress or onLoad instead).
        const tracked = manager && typeof manager.itemStart === "function" ? manager : null;
        if (tracked) tracked.itemStart(url);
        const end = () => { if (tracked) tracked.itemEnd(url); };
        if (typeof onLoad !== "function") {
            Promise.resolve().then(end);
            return;
        }
        let value;
        if (what === "OBJLoader") value = model(request, path);
        else if (what === "MTLLoader") value = { preload() {}, materials: {}, getAsArray: () => [], create: () => null };
        else if (what === "TextureLoader") value = THREE.Texture ? new THREE.Texture() : {};
        else if (what === "ImageLoader") value = globalThis.document.createElement("img");
        else {
            const files = record.files || {};
            const names = Object.keys(files);
            const found = names.find((n) => n === path) || names.find((n) => n.endsWith("/" + path) || path.endsWith("/" + n));
            if (found === undefined) return;
            value = files[found];
        }
        Promise.resolve().then(() => {
            try {
                onLoad(value);
            } finally {
                end();
            }
        });
    }

    // An OBJ's stand-in: one mesh, a quad in the XZ plane with normals and uv, as three.js's
    // OBJLoader hands it over (a Group whose child isMesh, with BufferGeometry attributes).
    function model(request, path) {
        const position = new Float32Array([-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, -1, 1, 0, 1, -1, 0, 1]);
        const normal = new Float32Array([0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0]);
        const uv = new Float32Array([0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1]);
        // Each array carries its request, so a draw of it says which model it is.
        for (const array of [position, normal, uv]) array.shadowlabRequest = request;
        const attribute = (array, size) => ({ array, itemSize: size, count: array.length / size });
        const color = (r, g, b) => (THREE.Color ? new THREE.Color(r, g, b) : { r, g, b, toArray: () => [r, g, b] });
        const mesh = {
            isMesh: true,
            name: path,
            shadowlabRequest: request,
            geometry: { attributes: { position: attribute(position, 3), normal: attribute(normal, 3), uv: attribute(uv, 2) }, index: null },
            material: { name: "stand-in", map: null, color: color(1, 1, 1), specular: color(0, 0, 0) },
        };
        const group = {
            isGroup: true,
            children: [mesh],
            traverse(f) { f(group); f(mesh); },
        };
        return group;
    }
    function loader(what) {
        return function (manager) {
            this.manager = manager || THREE.DefaultLoadingManager;
            this.path = "";
            this.setPath = (p) => { this.path = String(p); return this; };
            this.setMaterials = (m) => { this.materials = m; return this; };
            this.setResourcePath = () => this;
            this.setCrossOrigin = () => this;
            this.setResponseType = () => this;
            this.load = (url, onLoad) => answer(what, this.path + String(url), onLoad, this.manager);
        };
    }
    THREE.FileLoader = loader("FileLoader");
    THREE.MTLLoader = loader("MTLLoader");
    THREE.OBJLoader = loader("OBJLoader");
    THREE.TextureLoader = loader("TextureLoader");
    THREE.ImageLoader = loader("ImageLoader");
    // three.js's own LoadingManager stays: the stand-in loaders report to it as its loaders do.

    // dat.gui: folders and controllers that keep the values the page gives them.
    function controller(object, property) {
        const c = {
            object,
            property,
            name: () => c, step: () => c, min: () => c, max: () => c, listen: () => c,
            onChange: (f) => { c.changed = f; return c; },
            onFinishChange: (f) => { c.finished = f; return c; },
            setValue: (v) => { if (object) object[property] = v; return c; },
            getValue: () => (object ? object[property] : undefined),
            updateDisplay: () => c,
        };
        return c;
    }
    function GUI() {
        this.add = (object, property) => controller(object, property);
        this.addColor = (object, property) => controller(object, property);
        this.addFolder = () => new GUI();
        this.open = () => this;
        this.close = () => this;
        this.hide = () => this;
        this.show = () => this;
        this.destroy = () => {};
        this.remember = () => {};
        this.domElement = globalThis.document.createElement("div");
    }
    globalThis.dat = { GUI, gui: { GUI } };
})();
