# bash completion for dembox (installed to share/bash-completion/completions)
_dembox() {
    local cur prev cmd
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD-1]}
    cmd=${COMP_WORDS[1]}
    if [ "$COMP_CWORD" -eq 1 ]; then
        COMPREPLY=($(compgen -W "run sweep analyze plot bench examples example help --version --help" -- "$cur"))
        return
    fi
    case $prev in
        -o|--output|--resume|--cache-dir) COMPREPLY=($(compgen -d -- "$cur")); return ;;
        --data) COMPREPLY=($(compgen -f -- "$cur")); return ;;
        --boundary) COMPREPLY=($(compgen -W "walls periodic" -- "$cur")); return ;;
        --set|--param)
            # the keys of `dembox help config`; a stage's as stages.0.KEY
            # (the parser wants the stage's index)
            COMPREPLY=($(compgen -W "$(dembox help config 2>/dev/null | awk '/^[a-z]/ && $1 != "stages.N.KEY" {sub(/^stages\.N\./, "stages.0.", $1); print $1"="}')" -- "$cur"))
            compopt -o nospace 2>/dev/null
            return ;;
    esac
    local opts
    case $cmd in
        run) opts="-o --output --set --threads --quiet --resume --max-steps --any-build --help" ;;
        sweep) opts="-o --output --set --param --jobs --threads --quiet --max-steps --collect --any-build --help" ;;
        bench) opts="--dim --n --steps --threads --data --cache-dir --no-cache --boundary --quiet --help" ;;
    esac
    case $cmd in
        run|sweep)
            if [[ $cur == -* ]]; then
                COMPREPLY=($(compgen -W "$opts" -- "$cur"))
            else
                COMPREPLY=($(compgen -W "$(dembox examples 2>/dev/null | awk '{print $1}')" -- "$cur") $(compgen -f -X '!*.cfg' -- "$cur") $(compgen -d -- "$cur"))
            fi ;;
        example) COMPREPLY=($(compgen -W "$(dembox examples 2>/dev/null | awk '{print $1}')" -- "$cur")) ;;
        help) COMPREPLY=($(compgen -W "run sweep analyze plot bench examples example config $(dembox help config 2>/dev/null | awk '/^[a-z]/ && $1 != "stages.N.KEY" {print $1}')" -- "$cur")) ;;
        analyze|plot) COMPREPLY=($(compgen -d -- "$cur")) ;;
        bench) COMPREPLY=($(compgen -W "$opts" -- "$cur")) ;;
    esac
}
complete -F _dembox dembox
