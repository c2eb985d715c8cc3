// shadowlab's own copy of the framework's interface: an OBJ with its MTL through three.js's
// loaders; each of its meshes gets a Phong material and a shadow material built with the light.
function loadOBJ(renderer, path, name, objMaterial, transform) {
    const manager = new THREE.LoadingManager();
    new THREE.MTLLoader(manager).setPath(path).load(name + '.mtl', function (materials) {
        if (materials && materials.preload) materials.preload();
        new THREE.OBJLoader(manager).setMaterials(materials).setPath(path).load(name + '.obj', function (object) {
            object.traverse(function (child) {
                if (!child.isMesh) return;
                const geo = child.geometry;
                const mat = Array.isArray(child.material) ? child.material[0] : child.material;
                const indices = Array.from({ length: geo.attributes.position.count }, (v, k) => k);
                const mesh = new Mesh({ name: 'aVertexPosition', array: geo.attributes.position.array },
                    { name: 'aNormalPosition', array: geo.attributes.normal.array },
                    { name: 'aTextureCoord', array: geo.attributes.uv.array },
                    indices, transform);
                const colorMap = new Texture();
                if (mat.map != null) colorMap.CreateImageTexture(renderer.gl, mat.map.image);
                else colorMap.CreateConstantTexture(renderer.gl, mat.color.toArray());
                const translation = [transform.modelTransX, transform.modelTransY, transform.modelTransZ];
                const scale = [transform.modelScaleX, transform.modelScaleY, transform.modelScaleZ];
                const light = renderer.lights[0].entity;
                if (objMaterial !== 'PhongMaterial') return;
                buildPhongMaterial(colorMap, mat.specular.toArray(), light, translation, scale,
                    './src/shaders/phongShader/phongVertex.glsl', './src/shaders/phongShader/phongFragment.glsl')
                    .then((data) => renderer.addMeshRender(new MeshRender(renderer.gl, mesh, data)));
                buildShadowMaterial(light, translation, scale,
                    './src/shaders/shadowShader/shadowVertex.glsl', './src/shaders/shadowShader/shadowFragment.glsl')
                    .then((data) => renderer.addShadowMeshRender(new MeshRender(renderer.gl, mesh, data)));
            });
        });
    });
}
