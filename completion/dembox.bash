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
        -o|--resume) COMPREPLY=($(compgen -d -- "$cur")); return ;;
        --set|--param)
            COMPREPLY=($(compgen -W "$(dembox help config 2>/dev/null | awk '/^[a-z]/ {print $1"="}')" -- "$cur"))
            compopt -o nospace 2>/dev/null
            return ;;
    esac
    case $cmd in
        run|sweep)
            if [[ $cur == -* ]]; then
                COMPREPLY=($(compgen -W "-o --set --threads --quiet --resume --max-steps --param --jobs --collect --any-build" -- "$cur"))
            else
                COMPREPLY=($(compgen -W "$(dembox examples 2>/dev/null | awk '{print $1}')" -- "$cur") $(compgen -f -X '!*.cfg' -- "$cur"))
            fi ;;
        example) COMPREPLY=($(compgen -W "$(dembox examples 2>/dev/null | awk '{print $1}')" -- "$cur")) ;;
        help) COMPREPLY=($(compgen -W "run sweep analyze plot bench examples example config $(dembox help config 2>/dev/null | awk '/^[a-z]/ {print $1}')" -- "$cur")) ;;
        analyze|plot) COMPREPLY=($(compgen -d -- "$cur")) ;;
        bench) COMPREPLY=($(compgen -W "--dim --n --steps --threads --data --cache-dir --no-cache --quiet" -- "$cur")) ;;
    esac
}
complete -F _dembox dembox
