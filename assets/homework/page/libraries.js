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

    // A request the check answers from `record.files` (the submission's own text files, by path),
    // or leaves pending.
    function answer(what, url, onLoad) {
        const path = String(url).replace(/^\.?\//, "");
        record.requests.push({ what, url: path });
        const files = record.files || {};
        const found = Object.keys(files).find((name) => name === path || name.endsWith("/" + path) || path.endsWith("/" + name));
        if (found !== undefined && typeof onLoad === "function") onLoad(files[found]);
    }
    function loader(what) {
        return function (manager) {
            this.manager = manager;
            this.path = "";
            this.setPath = (p) => { this.path = String(p); return this; };
            this.setMaterials = (m) => { this.materials = m; return this; };
            this.setResourcePath = () => this;
            this.setCrossOrigin = () => this;
            this.load = (url, onLoad) => answer(what, this.path + String(url), onLoad);
        };
    }
    THREE.FileLoader = loader("FileLoader");
    THREE.MTLLoader = loader("MTLLoader");
    THREE.OBJLoader = loader("OBJLoader");
    THREE.TextureLoader = loader("TextureLoader");
    THREE.ImageLoader = loader("ImageLoader");
    THREE.LoadingManager = function () {
        this.onProgress = null;
        this.onLoad = null;
        this.onError = null;
        this.setURLModifier = () => this;
    };

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
