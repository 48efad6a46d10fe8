//! `verify bounds`: its flags and run ([`verify::bounds`]).

use clap::Args;

#[derive(Args)]
pub struct BoundsArgs {
    #[arg(long, default_value_t = 1000)]
    count: usize,
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Only this bound (repeat or separate by commas): sphere, torus, shell, slab, hull,
    /// node-sphere, node-torus, patch-lower, subdivision, sectors, kernel, leaf-stages,
    /// closed-form, convex, motion-rounding, motion-speed.
    #[arg(long, value_delimiter = ',')]
    bound: Vec<String>,
    /// Worker threads.
    #[arg(long, default_value_t = 1)]
    threads: usize,
}

impl BoundsArgs {
    pub fn run(self) {
        let Self {
            count,
            seed,
            bound,
            threads,
        } = self;
        let mut bounds = Vec::new();
        for name in &bound {
            match verify::bounds::Bound::from_name(name) {
                Some(b) => bounds.push(b),
                None => {
                    eprintln!("unknown bound {name:?}");
                    std::process::exit(2);
                }
            }
        }
        let r = verify::bounds::run(&verify::bounds::Options {
            count,
            seed,
            bounds,
            threads,
        });
        println!("{r}");
        if r.violations() > 0 {
            std::process::exit(1);
        }
    }
}
