//! Macros of the `kani` stand-in: `#[kani::proof]` keeps the harness function (so the same
//! source compiles under real Kani) and adds a `#[test]` that runs it through the stand-in's
//! explicit-state enumerator (or seeded sampler); `#[kani::unwind]`, `#[kani::solver]`,
//! `#[kani::should_panic]` and the stand-in's own `#[kani::samples]` are read by `proof` (put `#[kani::proof]` first); `#[derive(kani::Arbitrary)]` makes every
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
/// body), and under `cargo test` a `#[test]` runs it for every choice of its `kani::any()`
/// values (or a seeded sample when a domain is too wide) through `HARNESS.check()`.
#[proc_macro_attribute]
pub fn proof(_attr: TokenStream, item: TokenStream) -> TokenStream {
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
    f.attrs.retain(|a| {
        !["should_panic", "unwind", "solver", "stub", "samples"]
            .iter()
            .any(|n| is_kani_attr(a, n))
    });
    let mut covers = Vec::new();
    covers_in(f.block.to_token_stream(), &mut covers);
    let name = &f.sig.ident;
    let vis = &f.vis;
    let test = format_ident!("{}_standin", name);
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
