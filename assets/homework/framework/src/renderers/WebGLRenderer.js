// shadowlab's own copy of the framework's interface: per light, its cube, the shadow pass into its
// framebuffer, then the camera pass with uLightPos.
class WebGLRenderer {
    meshes = [];
    shadowMeshes = [];
    lights = [];

    constructor(gl, camera) {
        this.gl = gl;
        this.camera = camera;
    }

    addLight(light) {
        this.lights.push({ entity: light, meshRender: new MeshRender(this.gl, light.mesh, light.mat) });
    }

    addMeshRender(mesh) {
        this.meshes.push(mesh);
    }

    addShadowMeshRender(mesh) {
        this.shadowMeshes.push(mesh);
    }

    render() {
        const gl = this.gl;
        gl.clearColor(0.0, 0.0, 0.0, 1.0);
        gl.clearDepth(1.0);
        gl.enable(gl.DEPTH_TEST);
        gl.depthFunc(gl.LEQUAL);
        for (const light of this.lights) {
            light.meshRender.mesh.transform.translate = light.entity.lightPos;
            light.meshRender.draw(this.camera);
            if (light.entity.hasShadowMap == true) {
                for (const mesh of this.shadowMeshes) mesh.draw(this.camera);
            }
            for (const mesh of this.meshes) {
                gl.useProgram(mesh.shader.program.glShaderProgram);
                gl.uniform3fv(mesh.shader.program.uniforms.uLightPos, light.entity.lightPos);
                mesh.draw(this.camera);
            }
        }
    }
}
