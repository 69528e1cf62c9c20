//! Macros of the `kani` stand-in: `#[kani::proof]` keeps the harness function (so the same
//! source compiles under real Kani) and adds a `#[test]` that runs it through the stand-in's
//! explicit-state enumerator (or seeded sampler); `#[kani::unwind]`, `#[kani::solver]`,
//! `#[kani::should_panic]`, `#[kani::stub]`, `#[kani::stub_verified]` and the stand-in's own
//! `#[kani::samples]` are read by `proof` and `proof_for_contract` (put those first);
//! `#[kani::requires]`, `#[kani::ensures]` and `#[kani::modifies]` wrap a function so that its
//! contract is checked inside a stand-in harness run; `#[derive(kani::Arbitrary)]` makes every
//! value of a type a choice.

use proc_macro::TokenStream;
use quote::{format_ident, quote, ToTokens};
use syn::{parse_macro_input, Data, DeriveInput, Fields, ItemFn};

fn is_kani_attr(attr: &syn::Attribute, name: &str) -> bool {
    let segs: Vec<String> = attr
        .path()
        .segments
        .iter()
        .map(|s| s.ident.to_string())
        .collect();
    segs.last().is_some_and(|l| l == name) && (segs.len() == 1 || segs[0] == "kani")
}

/// The messages of the `cover!` calls (and `kani::cover(..)` calls) written in a harness body,
/// as the stand-in's `cover!` names them: `cover!()` is `"cover location"`, `cover!(c)` is
/// `"cover condition: c"` (compared whitespace-insensitively), `cover!(c, "msg")` is `msg`.
/// A message that is not a string literal is not listed (the run still records the call).
fn covers_in(ts: proc_macro2::TokenStream, out: &mut Vec<String>) {
    use proc_macro2::{Delimiter, TokenTree};
    let tokens: Vec<TokenTree> = ts.into_iter().collect();
    let punct =
        |i: usize, c: char| matches!(tokens.get(i), Some(TokenTree::Punct(p)) if p.as_char() == c);
    let ident = |i: usize, n: &str| matches!(tokens.get(i), Some(TokenTree::Ident(x)) if x == n);
    for (i, t) in tokens.iter().enumerate() {
        let TokenTree::Group(g) = t else { continue };
        let is_macro = i >= 2 && punct(i - 1, '!') && ident(i - 2, "cover");
        let is_call = g.delimiter() == Delimiter::Parenthesis
            && i >= 4
            && ident(i - 1, "cover")
            && punct(i - 2, ':')
            && punct(i - 3, ':')
            && ident(i - 4, "kani");
        if !(is_macro || is_call) {
            covers_in(g.stream(), out);
            continue;
        }
        // Split the arguments at top-level commas.
        let mut args: Vec<proc_macro2::TokenStream> = vec![proc_macro2::TokenStream::new()];
        for t in g.stream() {
            if matches!(&t, TokenTree::Punct(p) if p.as_char() == ',') {
                args.push(proc_macro2::TokenStream::new());
            } else {
                args.last_mut().expect("non-empty").extend([t]);
            }
        }
        args.retain(|a| !a.is_empty());
        let message = match (is_macro, args.len()) {
            (true, 0) => Some("cover location".to_string()),
            (true, 1) => Some(format!("cover condition: {}", args[0])),
            (_, 2) => syn::parse2::<syn::LitStr>(args[1].clone())
                .ok()
                .map(|l| l.value()),
            _ => None,
        };
        out.extend(message);
    }
}

/// Marks a harness: the function stays as written (so the same source compiles under real
/// Kani); next to it, a module of the same name holds `HARNESS: kani::Harness` (name,
/// `should_panic`, the stated sample count, the messages of the covers written in the body, the
/// contract it proves, the stubs it names, the body), and under `cargo test` a `#[test]` runs it
/// for every choice of its `kani::any()` values (or a seeded sample when a domain is too wide)
/// through `HARNESS.check()`.
#[proc_macro_attribute]
pub fn proof(_attr: TokenStream, item: TokenStream) -> TokenStream {
    harness(item, None)
}

/// `#[kani::proof_for_contract(f)]`: a harness that proves the contract of `f`. The stand-in
/// runs it like a `#[kani::proof]` harness; during the run, `f`'s precondition is *assumed* at
/// each of its calls (an execution violating it is pruned, as Kani assumes it) and its
/// postcondition asserted, and a run in which `f` is never called fails (nothing was proved).
#[proc_macro_attribute]
pub fn proof_for_contract(attr: TokenStream, item: TokenStream) -> TokenStream {
    let target: proc_macro2::TokenStream = attr.into();
    harness(item, Some(path_string(&target)))
}

/// A path as written, without spaces (`Q::<i16>::checked_add`, `truecost_kernel::…::gcd`).
fn path_string(ts: &proc_macro2::TokenStream) -> String {
    ts.to_string()
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect()
}

/// The paths named by the `#[kani::<name>(…)]` attributes of `attrs` (each attribute's whole
/// argument list, as written).
fn attr_args(attrs: &[syn::Attribute], name: &str) -> Vec<String> {
    attrs
        .iter()
        .filter(|a| is_kani_attr(a, name))
        .filter_map(|a| match &a.meta {
            syn::Meta::List(l) => Some(path_string(&l.tokens)),
            _ => None,
        })
        .collect()
}

fn harness(item: TokenStream, contract: Option<String>) -> TokenStream {
    let mut f = parse_macro_input!(item as ItemFn);
    let should_panic = f.attrs.iter().any(|a| is_kani_attr(a, "should_panic"));
    let samples: Option<syn::LitInt> =
        f.attrs
            .iter()
            .find(|a| is_kani_attr(a, "samples"))
            .map(|a| {
                a.parse_args()
                    .expect("#[kani::samples(N)] takes one integer")
            });
    let samples = match samples {
        Some(n) => quote!(#n),
        None => quote!(::kani::SAMPLES),
    };
    let verified = attr_args(&f.attrs, "stub_verified");
    let stubs = attr_args(&f.attrs, "stub");
    f.attrs.retain(|a| {
        ![
            "should_panic",
            "unwind",
            "solver",
            "stub",
            "stub_verified",
            "samples",
        ]
        .iter()
        .any(|n| is_kani_attr(a, n))
    });
    let mut covers = Vec::new();
    covers_in(f.block.to_token_stream(), &mut covers);
    let name = &f.sig.ident;
    let vis = &f.vis;
    let test = format_ident!("{}_standin", name);
    let contract = match contract {
        Some(c) => quote!(::core::option::Option::Some(#c)),
        None => quote!(::core::option::Option::None),
    };
    quote! {
        #f
        #[doc(hidden)]
        #[allow(missing_docs)]
        #vis mod #name {
            /// The harness as the stand-in runs it.
            pub const HARNESS: ::kani::Harness = ::kani::Harness {
                name: stringify!(#name),
                should_panic: #should_panic,
                samples: #samples,
                covers: &[#(#covers),*],
                contract: #contract,
                stub_verified: &[#(#verified),*],
                stubs: &[#(#stubs),*],
                body: super::#name,
            };
        }
        #[cfg(test)]
        #[test]
        fn #test() {
            let summary = #name::HARNESS.check();
            ::std::eprintln!("{}", summary);
        }
    }
    .into()
}

/// Replaces every `old(e)` call in an `ensures` closure by a variable bound to `e` before the
/// function's body runs (Kani's `old`), collecting the expressions.
struct Olds(Vec<syn::Expr>);

impl syn::visit_mut::VisitMut for Olds {
    fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
        if let syn::Expr::Call(c) = e {
            if let syn::Expr::Path(p) = &*c.func {
                if p.path.is_ident("old") && c.args.len() == 1 {
                    let inner = c.args[0].clone();
                    let var = format_ident!("__kani_old_{}", self.0.len());
                    self.0.push(inner);
                    *e = syn::parse_quote!(#var.expect("old value"));
                    return;
                }
            }
        }
        syn::visit_mut::visit_expr_mut(self, e);
    }
}

/// The contract attributes (`requires`, `ensures`, `modifies`): the outermost one reads every
/// contract attribute of the function (its own, then the ones below it), removes them, and
/// wraps the body. Outside a stand-in harness run the wrapper reads one thread-local flag and
/// runs the body unchanged; inside one it checks the precondition before the body (assumed when
/// the harness is the function's `proof_for_contract`, asserted otherwise — a caller that
/// violates it is a failure, as at a `stub_verified` call under Kani) and every postcondition
/// after it (asserted).
fn contract(kind: &str, attr: TokenStream, item: TokenStream) -> TokenStream {
    let mut f = parse_macro_input!(item as ItemFn);
    let mut requires: Vec<syn::Expr> = Vec::new();
    let mut ensures: Vec<syn::Expr> = Vec::new();
    let mut push = |kind: &str, tokens: proc_macro2::TokenStream| -> syn::Result<()> {
        match kind {
            "requires" => requires.push(syn::parse2(tokens)?),
            "ensures" => ensures.push(syn::parse2(tokens)?),
            _ => {} // `modifies`: the postconditions state what is left unchanged
        }
        Ok(())
    };
    if let Err(e) = push(kind, attr.into()) {
        return e.to_compile_error().into();
    }
    let mut rest = Vec::new();
    for a in std::mem::take(&mut f.attrs) {
        let k = ["requires", "ensures", "modifies"]
            .into_iter()
            .find(|k| is_kani_attr(&a, k));
        match (k, &a.meta) {
            (Some(k), syn::Meta::List(l)) => {
                if let Err(e) = push(k, l.tokens.clone()) {
                    return e.to_compile_error().into();
                }
            }
            _ => rest.push(a),
        }
    }
    f.attrs = rest;
    let mut olds = Olds(Vec::new());
    for e in &mut ensures {
        syn::visit_mut::VisitMut::visit_expr_mut(&mut olds, e);
    }
    let old_vars = (0..olds.0.len()).map(|i| format_ident!("__kani_old_{}", i));
    let old_exprs = olds.0.iter();
    let name = f.sig.ident.to_string();
    let ret = match &f.sig.output {
        syn::ReturnType::Default => quote!(()),
        syn::ReturnType::Type(_, t) => quote!(#t),
    };
    let req_texts = requires.iter().map(|r| r.to_token_stream().to_string());
    let ens_texts = ensures.iter().map(|r| r.to_token_stream().to_string());
    let block = &f.block;
    let body = quote! {{
        let __kani_check = ::kani::__contract_checks();
        let __kani_target = __kani_check
            && ::kani::__contract_is_target(::core::module_path!(), #name);
        if __kani_check {
            #( ::kani::__contract_requires(#requires, __kani_target, #name, #req_texts); )*
        }
        #( let #old_vars = if __kani_check { ::core::option::Option::Some(#old_exprs) } else { ::core::option::Option::None }; )*
        #[allow(clippy::redundant_closure_call)]
        let __kani_result: #ret = (|| #block)();
        if __kani_check {
            #( ::kani::__contract_ensures((#ensures)(&__kani_result), #name, #ens_texts); )*
        }
        __kani_result
    }};
    f.block = Box::new(syn::parse2(body).expect("a block"));
    f.into_token_stream().into()
}

/// A precondition (Kani's `#[kani::requires(cond)]`; see the private `contract` for the stand-in's
/// checks). Needs `-Z function-contracts` under Kani.
#[proc_macro_attribute]
pub fn requires(attr: TokenStream, item: TokenStream) -> TokenStream {
    contract("requires", attr, item)
}

/// A postcondition, a closure over a reference to the result (Kani's
/// `#[kani::ensures(|result| cond)]`, with `old(e)` for the value of `e` before the call).
#[proc_macro_attribute]
pub fn ensures(attr: TokenStream, item: TokenStream) -> TokenStream {
    contract("ensures", attr, item)
}

/// What the function may write (Kani's `#[kani::modifies(…)]`); the stand-in does not track
/// writes: the postconditions state what stays unchanged.
#[proc_macro_attribute]
pub fn modifies(attr: TokenStream, item: TokenStream) -> TokenStream {
    contract("modifies", attr, item)
}

fn misplaced(name: &str) -> TokenStream {
    let msg = format!("kani stand-in: put #[kani::proof] before #[kani::{name}]");
    quote!(compile_error!(#msg);).into()
}

/// Loop bound for Kani (read by `#[kani::proof]`).
#[proc_macro_attribute]
pub fn unwind(_attr: TokenStream, _item: TokenStream) -> TokenStream {
    misplaced("unwind")
}

/// SAT solver for Kani (read by `#[kani::proof]`).
#[proc_macro_attribute]
pub fn solver(_attr: TokenStream, _item: TokenStream) -> TokenStream {
    misplaced("solver")
}

/// Stand-in only (write it as `#[cfg_attr(not(kani), kani::samples(N))]`): the number of
/// executions when the harness is sampled (read by `#[kani::proof]`).
#[proc_macro_attribute]
pub fn samples(_attr: TokenStream, _item: TokenStream) -> TokenStream {
    misplaced("samples")
}

/// Kani replaces the first function by the second in this harness (read by `#[kani::proof]`;
/// the stand-in cannot replace a call in another crate, so it runs the real function and lists
/// the stub in the run's summary).
#[proc_macro_attribute]
pub fn stub(_attr: TokenStream, _item: TokenStream) -> TokenStream {
    misplaced("stub")
}

/// Kani replaces the function by its proven contract in this harness (read by
/// `#[kani::proof]`; the stand-in runs the real function with its contract checked).
#[proc_macro_attribute]
pub fn stub_verified(_attr: TokenStream, _item: TokenStream) -> TokenStream {
    misplaced("stub_verified")
}

/// The harness must fail (read by `#[kani::proof]`).
#[proc_macro_attribute]
pub fn should_panic(_attr: TokenStream, _item: TokenStream) -> TokenStream {
    misplaced("should_panic")
}

/// `#[derive(kani::Arbitrary)]`: structs take every field from `kani::any()`; enums choose a
/// variant (one choice point with as many values as variants).
#[proc_macro_derive(Arbitrary)]
pub fn derive_arbitrary(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    let name = &input.ident;
    let build = |fields: &Fields, path: proc_macro2::TokenStream| match fields {
        Fields::Named(n) => {
            let f = n.named.iter().map(|f| f.ident.clone());
            quote!(#path { #(#f: ::kani::any()),* })
        }
        Fields::Unnamed(u) => {
            let f = u.unnamed.iter().map(|_| quote!(::kani::any()));
            quote!(#path ( #(#f),* ))
        }
        Fields::Unit => quote!(#path),
    };
    let body = match &input.data {
        Data::Struct(s) => build(&s.fields, quote!(#name)),
        Data::Enum(e) => {
            let n = e.variants.len() as u64;
            let arms = e.variants.iter().enumerate().map(|(i, v)| {
                let i = i as u64;
                let ident = &v.ident;
                let value = build(&v.fields, quote!(#name::#ident));
                quote!(#i => #value,)
            });
            quote!(match ::kani::__choose(#n) { #(#arms)* _ => unreachable!() })
        }
        Data::Union(_) => quote!(compile_error!("kani stand-in: unions are not Arbitrary")),
    };
    quote! {
        impl ::kani::Arbitrary for #name {
            fn any() -> Self { #body }
        }
    }
    .into()
}
