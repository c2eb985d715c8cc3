// shadowlab's own copy of the framework's interface: uniforms by name ({type, value}), the
// attributes, the two shader sources and the framebuffer the material draws into (null: the
// canvas).
class Material {
    #flatten_uniforms;
    #flatten_attribs;
    #vsSrc;
    #fsSrc;

    constructor(uniforms, attribs, vsSrc, fsSrc, frameBuffer) {
        this.uniforms = uniforms;
        this.attribs = attribs;
        this.#vsSrc = vsSrc;
        this.#fsSrc = fsSrc;
        this.#flatten_uniforms = ['uViewMatrix', 'uModelMatrix', 'uProjectionMatrix', 'uCameraPos', 'uLightPos'];
        for (const name in uniforms) this.#flatten_uniforms.push(name);
        this.#flatten_attribs = attribs;
        this.frameBuffer = frameBuffer;
    }

    setMeshAttribs(extraAttribs) {
        for (const name of extraAttribs) this.#flatten_attribs.push(name);
    }

    compile(gl) {
        return new Shader(gl, this.#vsSrc, this.#fsSrc, {
            uniforms: this.#flatten_uniforms,
            attribs: this.#flatten_attribs,
        });
    }
}
