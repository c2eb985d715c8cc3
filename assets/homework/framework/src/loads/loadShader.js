// shadowlab's own copy of the framework's interface: a shader file's text, through three.js's
// FileLoader.
async function loadShaderFile(filename) {
    return new Promise((resolve) => {
        new THREE.FileLoader().load(filename, (data) => resolve(data));
    });
}

async function getShaderString(filename) {
    return await loadShaderFile(filename);
}
