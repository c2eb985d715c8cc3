//! The syntax tree the parser builds and the evaluator walks.
//!
//! Its depth is bounded by `Limits::nesting` (the parser counts every level, including
//! each link of a long `a + b + c` or `a.b.c` chain), so walking and dropping it recurse
//! a bounded number of times.

use std::sync::Arc;

pub(super) type Name = Arc<str>;

pub(super) struct Expr {
    pub kind: ExprKind,
    pub line: usize,
}

pub(super) enum ExprKind {
    Num(f64),
    Str(Name),
    Template {
        quasis: Vec<Name>,
        exprs: Vec<Expr>,
    },
    Bool(bool),
    Null,
    Ident(Name),
    This,
    Array(Vec<Item>),
    Object(Vec<ObjProp>),
    Function(Arc<FuncDef>),
    Class(Arc<ClassDef>),
    Unary(UnaryOp, Box<Expr>),
    Update {
        inc: bool,
        prefix: bool,
        target: Box<Expr>,
    },
    Binary(BinOp, Box<Expr>, Box<Expr>),
    Logical(LogicOp, Box<Expr>, Box<Expr>),
    Cond(Box<Expr>, Box<Expr>, Box<Expr>),
    Assign {
        op: AssignOp,
        target: Box<Expr>,
        value: Box<Expr>,
        strict: bool,
    },
    Seq(Vec<Expr>),
    Member {
        obj: Box<Expr>,
        prop: Name,
        optional: bool,
    },
    Index {
        obj: Box<Expr>,
        index: Box<Expr>,
        optional: bool,
    },
    Call {
        callee: Box<Expr>,
        args: Vec<Item>,
        optional: bool,
    },
    New {
        callee: Box<Expr>,
        args: Vec<Item>,
    },
    SuperCall(Vec<Item>),
    SuperMember(Name),
    /// The end of a chain containing `?.`: a nullish link makes the whole chain undefined.
    OptChain(Box<Expr>),
}

/// An element of an array literal or an argument list.
pub(super) enum Item {
    Hole,
    Plain(Expr),
    Spread(Expr),
}

pub(super) enum PropKey {
    Name(Name),
    Computed(Expr),
}

pub(super) enum ObjProp {
    Value(PropKey, Expr),
    Getter(PropKey, Arc<FuncDef>),
    Setter(PropKey, Arc<FuncDef>),
    Spread(Expr),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum UnaryOp {
    Neg,
    Plus,
    Not,
    BitNot,
    Typeof,
    Void,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Pow,
    Eq,
    Ne,
    StrictEq,
    StrictNe,
    Lt,
    Gt,
    Le,
    Ge,
    BitAnd,
    BitOr,
    BitXor,
    Shl,
    Shr,
    UShr,
    InstanceOf,
    In,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum LogicOp {
    And,
    Or,
    Nullish,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum AssignOp {
    Assign,
    Op(BinOp),
    Logic(LogicOp),
}

pub(super) enum Pattern {
    Ident(Name),
    Array { items: Vec<Option<PatItem>>, rest: Option<Box<Pattern>> },
    Object { props: Vec<(PropKey, PatItem)>, rest: Option<Name> },
}

pub(super) struct PatItem {
    pub target: Pattern,
    pub default: Option<Expr>,
}

pub(super) enum FuncBody {
    Block(Vec<Stmt>),
    Expr(Box<Expr>),
}

pub(super) struct FuncDef {
    pub name: Option<Name>,
    pub params: Vec<PatItem>,
    pub rest: Option<Pattern>,
    pub body: FuncBody,
    pub arrow: bool,
    pub uses_arguments: bool,
    /// `var` names declared anywhere in the body (not in nested functions): hoisted.
    pub var_names: Vec<Name>,
    pub line: usize,
    pub end_line: usize,
}

pub(super) struct ClassDef {
    pub name: Option<Name>,
    pub parent: Option<Expr>,
    pub ctor: Option<Arc<FuncDef>>,
    pub members: Vec<ClassMember>,
    pub line: usize,
}

pub(super) struct ClassMember {
    pub is_static: bool,
    pub key: PropKey,
    pub kind: MemberKind,
    pub line: usize,
}

pub(super) enum MemberKind {
    Method(Arc<FuncDef>),
    Getter(Arc<FuncDef>),
    Setter(Arc<FuncDef>),
    Field(Option<Expr>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum DeclKind {
    Var,
    Let,
    Const,
}

pub(super) struct Stmt {
    pub kind: StmtKind,
    pub line: usize,
}

pub(super) enum StmtKind {
    Expr(Expr),
    Decl(DeclKind, Vec<(Pattern, Option<Expr>)>),
    Function(Arc<FuncDef>),
    Class(Arc<ClassDef>),
    Return(Option<Expr>),
    If(Expr, Box<Stmt>, Option<Box<Stmt>>),
    Block(Vec<Stmt>),
    For {
        init: Option<Box<Stmt>>,
        test: Option<Expr>,
        update: Option<Expr>,
        body: Box<Stmt>,
    },
    /// `for (x of xs)` and, with `is_in`, `for (k in obj)`.
    ForEach {
        decl: Option<DeclKind>,
        target: Pattern,
        iter: Expr,
        body: Box<Stmt>,
        is_in: bool,
    },
    While(Expr, Box<Stmt>),
    DoWhile(Box<Stmt>, Expr),
    Break,
    Continue,
    Throw(Expr),
    Try {
        body: Vec<Stmt>,
        param: Option<Pattern>,
        handler: Option<Vec<Stmt>>,
        finally: Option<Vec<Stmt>>,
    },
    Switch(Expr, Vec<Case>),
    Empty,
}

pub(super) struct Case {
    pub test: Option<Expr>,
    pub body: Vec<Stmt>,
}

pub(super) struct Program {
    pub body: Vec<Stmt>,
    pub var_names: Vec<Name>,
    pub notes: Vec<String>,
}
