//! What a name is where it is used, as far as WebGL's rules need: a loop index, a constant, or a
//! variable that is neither (a uniform, a varying, a parameter, a variable). Read from the
//! student's tokens with the scopes of braces, parameters and `for` headers.

use super::preprocess::Preprocessed;
use crate::homework::lex::{Kind, Token, tokens};

/// The built-in types of GLSL ES 1.00 a declaration can start with.
pub const TYPES: [&str; 19] = [
    "void",
    "bool",
    "int",
    "float",
    "vec2",
    "vec3",
    "vec4",
    "bvec2",
    "bvec3",
    "bvec4",
    "ivec2",
    "ivec3",
    "ivec4",
    "mat2",
    "mat3",
    "mat4",
    "sampler2D",
    "samplerCube",
    "struct",
];

/// Most tokens whose names and loops are followed.
const MAX_SCOPED_TOKENS: usize = 50_000;

/// What a declared name is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeclKind {
    /// `const` (a constant expression where its initializer is one).
    Const,
    /// The index a `for` header declares.
    LoopIndex,
    Uniform,
    Attribute,
    Varying,
    Parameter,
    Variable,
}

impl DeclKind {
    pub fn describe(self) -> &'static str {
        match self {
            DeclKind::Const => "a constant",
            DeclKind::LoopIndex => "a loop index",
            DeclKind::Uniform => "a uniform",
            DeclKind::Attribute => "an attribute",
            DeclKind::Varying => "a varying",
            DeclKind::Parameter => "a function parameter",
            DeclKind::Variable => "a variable",
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub struct Decl {
    pub kind: DeclKind,
    /// The token of its name.
    pub at: usize,
    /// The tokens it is visible over (from its name to the end of its scope).
    pub visible: (usize, usize),
    pub line: usize,
}

/// A `for` statement: its `for` token, its header's parentheses, and its body's last token.
#[derive(Clone, Copy, Debug)]
pub struct ForLoop {
    pub at: usize,
    pub open: usize,
    pub close: usize,
    pub body_end: usize,
}

/// The student's shader as the rules read it: tokens with two- and three-byte operators joined,
/// the `#define`s and compiled lines, every declaration with its scope, every `for`.
pub struct Shader<'a> {
    pub source: &'a str,
    pub toks: Vec<Token>,
    pub pre: Preprocessed,
    pub decls: Vec<Decl>,
    pub loops: Vec<ForLoop>,
    /// Functions the student defines (or declares), by name.
    pub functions: Vec<String>,
    /// The `[` tokens that give an array's size in a declaration (not an index).
    pub array_sizes: Vec<usize>,
    /// For each token, the index of the bracket closing it where it opens one.
    closing: Vec<Option<usize>>,
    /// For each token, how many `(` and `{` are open before it, and the innermost open `{`.
    paren_depth: Vec<i32>,
    brace_depth: Vec<i32>,
    open_brace: Vec<Option<usize>>,
    /// `decls` by name, in order.
    by_name: std::collections::HashMap<&'a str, Vec<usize>>,
}

/// What a name used at a token resolves to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolved {
    Decl(Decl),
    Macro,
    /// Not declared in the shader (a built-in, or a name this reading does not follow).
    Unknown,
}

impl PartialEq for Decl {
    fn eq(&self, other: &Decl) -> bool {
        self.at == other.at
    }
}
impl Eq for Decl {}

impl<'a> Shader<'a> {
    pub fn read(source: &'a str) -> Shader<'a> {
        let raw = tokens(source);
        let pre = super::preprocess::preprocess(source, &raw);
        // Only what WebGL compiles: directives and branches not taken are left out.
        let toks =
            join_operators(source, raw.into_iter().filter(|t| !t.in_directive && pre.compiled(t.line)));
        let closing = closing_brackets(source, &toks);
        let (mut paren_depth, mut brace_depth, mut open_brace) = (Vec::new(), Vec::new(), Vec::new());
        let (mut parens, mut braces) = (0i32, Vec::new());
        for t in &toks {
            paren_depth.push(parens);
            brace_depth.push(braces.len() as i32);
            open_brace.push(braces.last().copied());
            match &source[t.start..t.end] {
                "(" => parens += 1,
                ")" => parens -= 1,
                "{" => braces.push(paren_depth.len() - 1),
                "}" => {
                    braces.pop();
                }
                _ => {}
            }
        }
        let mut shader = Shader {
            source,
            toks,
            pre,
            decls: Vec::new(),
            loops: Vec::new(),
            functions: Vec::new(),
            array_sizes: Vec::new(),
            closing,
            paren_depth,
            brace_depth,
            open_brace,
            by_name: std::collections::HashMap::new(),
        };
        // A homework shader has 1,000 to 10,000 tokens; past this many, names are not followed
        // (nothing is refused for what a name is), so that a machine-made shader of a megabyte
        // stays quick to read.
        if shader.toks.len() > MAX_SCOPED_TOKENS {
            return shader;
        }
        shader.find_loops();
        shader.find_declarations();
        for (k, d) in shader.decls.iter().enumerate() {
            let name = &source[shader.toks[d.at].start..shader.toks[d.at].end];
            shader.by_name.entry(name).or_default().push(k);
        }
        shader.functions.sort();
        shader.functions.dedup();
        shader.array_sizes.sort_unstable();
        shader
    }

    pub fn text(&self, i: usize) -> &'a str {
        self.toks.get(i).map_or("", |t| &self.source[t.start..t.end])
    }

    pub fn line(&self, i: usize) -> usize {
        self.toks.get(i).map_or(1, |t| t.line)
    }

    pub fn closing(&self, open: usize) -> Option<usize> {
        self.closing.get(open).copied().flatten()
    }

    pub fn is_ident(&self, i: usize) -> bool {
        self.toks.get(i).is_some_and(|t| t.kind == Kind::Ident)
    }

    /// The last token of the statement starting at `from` (a `{...}` block, or up to its `;`).
    fn statement_end(&self, from: usize) -> usize {
        if self.text(from) == "{" {
            return self.closing(from).unwrap_or(self.toks.len().saturating_sub(1));
        }
        if (self.text(from) == "for" || self.text(from) == "while")
            && let Some(close) = self.closing(from + 1)
        {
            return self.statement_end(close + 1);
        }
        if self.text(from) == "if"
            && let Some(close) = self.closing(from + 1)
        {
            let then_end = self.statement_end(close + 1);
            if self.text(then_end + 1) == "else" {
                return self.statement_end(then_end + 2);
            }
            return then_end;
        }
        let mut depth = 0i32;
        for k in from..self.toks.len() {
            match self.text(k) {
                "(" | "[" | "{" => depth += 1,
                ")" | "]" | "}" => depth -= 1,
                ";" if depth <= 0 => return k,
                _ => {}
            }
        }
        self.toks.len().saturating_sub(1)
    }

    fn find_loops(&mut self) {
        for i in 0..self.toks.len() {
            if self.text(i) == "for"
                && self.text(i + 1) == "("
                && let Some(close) = self.closing(i + 1)
            {
                let body_end = self.statement_end(close + 1);
                self.loops.push(ForLoop { at: i, open: i + 1, close, body_end });
            }
        }
    }

    /// The innermost pair of braces around token `i`: (open, close), or the whole shader.
    fn enclosing_braces(&self, i: usize) -> (usize, usize) {
        let open = self.open_brace.get(i).copied().flatten();
        match open.and_then(|o| Some((o, self.closing(o)?))) {
            Some(pair) => pair,
            None => (0, self.toks.len()),
        }
    }

    fn find_declarations(&mut self) {
        let n = self.toks.len();
        let struct_names: Vec<&str> = (0..n)
            .filter(|&i| self.text(i) == "struct" && self.is_ident(i + 1))
            .map(|i| self.text(i + 1))
            .collect();
        let is_type = |s: &Shader, i: usize| TYPES.contains(&s.text(i)) || struct_names.contains(&s.text(i));
        let mut decls = Vec::new();
        let mut i = 0;
        while i < n {
            if !(is_type(self, i) && self.text(i) != "struct" && self.is_ident(i + 1)) || is_type(self, i + 1)
            {
                i += 1;
                continue;
            }
            let name_at = i + 1;
            // A function: its name is followed by its parameter list.
            if self.text(name_at + 1) == "(" && self.paren_depth(i) == 0 && self.brace_depth(i) == 0 {
                self.functions.push(self.text(name_at).to_string());
                if let Some(close) = self.closing(name_at + 1) {
                    let body = (self.text(close + 1) == "{").then(|| self.closing(close + 1)).flatten();
                    self.parameters(name_at + 1, close, body, &is_type, &mut decls);
                    i = close + 1;
                    continue;
                }
            }
            // Qualifiers before the type (precision ones aside).
            let mut q = i;
            let mut kind = DeclKind::Variable;
            while q > 0 {
                match self.text(q - 1) {
                    "highp" | "mediump" | "lowp" | "invariant" => {}
                    "const" => kind = DeclKind::Const,
                    "uniform" => kind = DeclKind::Uniform,
                    "attribute" => kind = DeclKind::Attribute,
                    "varying" => kind = DeclKind::Varying,
                    _ => break,
                }
                q -= 1;
            }
            let for_header = self.loops.iter().find(|l| q > 0 && l.open == q - 1);
            if let Some(l) = for_header {
                kind = DeclKind::LoopIndex;
                decls.push(Decl {
                    kind,
                    at: name_at,
                    visible: (name_at, l.body_end),
                    line: self.line(name_at),
                });
                i = name_at + 1;
                continue;
            }
            let end = self.statement_end(i);
            let scope_end = if self.brace_depth(i) == 0 { n } else { self.enclosing_braces(i).1 };
            // `float a = 1.0, b[2], c;`: each name at depth 0 after the type or a comma.
            let mut at = name_at;
            loop {
                if self.text(at + 1) == "[" {
                    self.array_sizes.push(at + 1);
                }
                decls.push(Decl { kind, at, visible: (at, scope_end), line: self.line(at) });
                let mut k = at + 1;
                let mut depth = 0i32;
                while k < end {
                    match self.text(k) {
                        "(" | "[" | "{" => depth += 1,
                        ")" | "]" | "}" => depth -= 1,
                        "," if depth == 0 => break,
                        _ => {}
                    }
                    k += 1;
                }
                if k < end && self.is_ident(k + 1) {
                    at = k + 1;
                } else {
                    break;
                }
            }
            i = end.max(i + 1);
        }
        self.decls = decls;
    }

    /// The parameters between `open` and `close`, visible over the function's `body`.
    fn parameters(
        &mut self,
        open: usize,
        close: usize,
        body: Option<usize>,
        is_type: &dyn Fn(&Shader, usize) -> bool,
        decls: &mut Vec<Decl>,
    ) {
        for k in open + 1..close {
            if is_type(self, k) && self.is_ident(k + 1) && matches!(self.text(k + 2), "," | ")" | "[") {
                if self.text(k + 2) == "[" {
                    self.array_sizes.push(k + 2);
                }
                let visible = (close, body.unwrap_or(close));
                decls.push(Decl { kind: DeclKind::Parameter, at: k + 1, visible, line: self.line(k + 1) });
            }
        }
    }

    fn paren_depth(&self, i: usize) -> i32 {
        self.paren_depth.get(i).copied().unwrap_or(0)
    }

    fn brace_depth(&self, i: usize) -> i32 {
        self.brace_depth.get(i).copied().unwrap_or(0)
    }

    /// Whether the student defines (or declares) a function of this name.
    pub fn defines_function(&self, name: &str) -> bool {
        self.functions.binary_search_by(|f| f.as_str().cmp(name)).is_ok()
    }

    /// Whether the `[` at `open` gives an array's size in a declaration.
    pub fn is_array_size(&self, open: usize) -> bool {
        self.array_sizes.binary_search(&open).is_ok()
    }

    /// The innermost declaration of `name` visible at token `at`.
    pub fn visible_decl(&self, name: &str, at: usize) -> Option<Decl> {
        self.by_name
            .get(name)?
            .iter()
            .map(|&k| self.decls[k])
            .filter(|d| d.visible.0 <= at && at <= d.visible.1)
            .max_by_key(|d| d.visible.0)
    }

    /// What the name at token `i` is there: the innermost declaration visible at `i`, a macro, or
    /// unknown. A field or swizzle (after `.`) is unknown.
    pub fn resolve(&self, i: usize) -> Resolved {
        if i > 0 && self.text(i - 1) == "." {
            return Resolved::Unknown;
        }
        let name = self.text(i);
        if let Some(d) = self.visible_decl(name, i) {
            return Resolved::Decl(d);
        }
        if self.pre.macros.contains_key(name) {
            return Resolved::Macro;
        }
        Resolved::Unknown
    }
}

/// Adjacent punctuation that makes one operator (`<=`, `+=`, `&&`, `<<=`...) as one token.
fn join_operators(source: &str, toks: impl Iterator<Item = Token>) -> Vec<Token> {
    const JOINED: [&str; 20] = [
        "<=", ">=", "==", "!=", "&&", "||", "^^", "++", "--", "+=", "-=", "*=", "/=", "%=", "<<", ">>", "&=",
        "|=", "^=", "<<=",
    ];
    let mut out: Vec<Token> = Vec::new();
    for t in toks {
        if let Some(last) = out.last_mut() {
            let joined = &source[last.start..t.end];
            if t.kind == Kind::Punct
                && last.kind == Kind::Punct
                && last.end == t.start
                && (JOINED.contains(&joined) || joined == ">>=")
            {
                last.end = t.end;
                continue;
            }
        }
        out.push(t);
    }
    out
}

/// For each `(`, `[` and `{`, the index of the token closing it.
fn closing_brackets(source: &str, toks: &[Token]) -> Vec<Option<usize>> {
    let mut closing = vec![None; toks.len()];
    let mut open: Vec<usize> = Vec::new();
    for (i, t) in toks.iter().enumerate() {
        match &source[t.start..t.end] {
            "(" | "[" | "{" => open.push(i),
            ")" | "]" | "}" => {
                if let Some(o) = open.pop() {
                    closing[o] = Some(i);
                }
            }
            _ => {}
        }
    }
    closing
}
